#include "cli_files.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/input_file.hpp"
#include "tellus/tiles/byte_source.hpp"

namespace tellus::cli {
namespace fs = std::filesystem;

namespace {

// The same file, by identity when both exist, else by normalised absolute name.
bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0) {
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  }
  std::error_code ec;
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

}  // namespace

Status checkCommandFiles(const CommandFiles& files) {
  std::vector<fs::path> inputs;
  for (const std::string& input : files.inputs) {
    if (isUrl(input)) continue;  // a store over HTTP: nothing local to check or protect
    if (Status regular = checkRegularInput(input); !regular) return regular;
    inputs.emplace_back(input);
  }
  for (const std::string& input : files.optionalInputs) {
    std::error_code ec;
    if (input.empty() || isUrl(input) || !fs::exists(fs::symlink_status(input, ec))) continue;
    if (Status regular = checkRegularInput(input); !regular) return regular;
    inputs.emplace_back(input);
  }
  protectInputFiles(inputs);
  for (std::size_t i = 0; i < files.outputs.size(); ++i) {
    const std::string& output = files.outputs[i];
    if (Status writable = checkOutputWritable(output); !writable) return writable;
    for (std::size_t j = 0; j < i; ++j) {
      if (sameFile(output, files.outputs[j])) {
        return makeError("'{}' is given for two outputs ('{}' too); give each its own file",
                         output, files.outputs[j]);
      }
    }
  }
  for (const std::string& folder : files.outputFolders) {
    std::error_code ec;
    if (fs::exists(folder, ec) && !fs::is_directory(folder, ec)) {
      return makeError("cannot write into '{}': it exists and is not a folder", folder);
    }
  }
  return {};
}

void addRendererReadFiles(CommandFiles& files, const fs::path& localInput,
                          const std::string& geoid, const std::string& drape,
                          const RendererSettings& settings) {
  for (const std::string& file : {geoid, drape}) {
    if (!file.empty()) files.inputs.push_back(file);
  }
  for (const RendererFamily* family : rendererFamilies()) {
    const std::any& values = settings.of(family->schema.family);
    for (const RendererOption& option : family->schema.options) {
      if (option.kind == OptionKind::Paths) {
        const OptionValue given = option.get(values);
        for (const std::string& file : std::get<std::vector<std::string>>(given))
          files.inputs.push_back(file);
      }
      if (option.kind != OptionKind::Path) continue;
      const std::string given = std::get<std::string>(option.get(values));
      std::error_code ec;
      if (!given.empty() && fs::is_directory(given, ec)) {
        for (const fs::directory_entry& entry : fs::directory_iterator(given, ec)) {
          if (entry.is_regular_file(ec)) files.optionalInputs.push_back(entry.path().string());
        }
      } else if (!given.empty()) {
        files.inputs.push_back(given);
      } else if (const fs::path beside = optionPathOrBesideInput(option, values, localInput);
                 !beside.empty()) {
        files.optionalInputs.push_back(beside.string());
      }
    }
  }
}

}  // namespace tellus::cli
