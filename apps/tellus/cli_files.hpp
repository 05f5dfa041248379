#pragma once
// The files a command reads and writes, checked in one place before the command runs
// (main.cpp): inputs must be regular files (a FIFO would hang the command, a device stream
// without end), outputs must be regular files or not exist, in a writable folder, and never one
// of the inputs under another name (same device and inode). The inputs are then protected for
// the whole run: every writer refuses them (atomic_output.hpp), also the files a command writes
// into an output folder.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus::cli {

struct CommandFiles {
  CommandFiles() = default;
  CommandFiles(std::vector<std::string> inputsRead, std::vector<std::string> outputsWritten,
               std::vector<std::string> foldersWritten)
      : inputs(std::move(inputsRead)),
        outputs(std::move(outputsWritten)),
        outputFolders(std::move(foldersWritten)) {}

  std::vector<std::string> inputs;         // files read (DEMs, a store, a keyframe path)
  std::vector<std::string> outputs;        // files written
  std::vector<std::string> outputFolders;  // folders written into (created when missing)
  // Files read when they exist (a renderer's file beside the input, a texture set's images): checked
  // and protected like the inputs when present, no error when absent.
  std::vector<std::string> optionalInputs;
};

// The files a renderer command (render, bench, view) reads besides its DEM inputs: the geoid
// and drape, and every renderer option's files (the schemas' Path and Paths options): a given
// file is an input, a given folder's files (the Blue Marble set) and a file found beside the
// input (a renderer option's besideInputExtension; `localInput`: the first input when it is a
// local file, cli_support's localInputPath) are optional inputs.
void addRendererReadFiles(CommandFiles& files, const std::filesystem::path& localInput,
                          const std::string& geoid, const std::string& drape,
                          const RendererSettings& settings);

// Checks `files` as described above and protects the inputs. Errors name the file and why.
Status checkCommandFiles(const CommandFiles& files);

}  // namespace tellus::cli
