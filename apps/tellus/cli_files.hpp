#pragma once
// The files a command reads and writes, checked in one place before the command runs
// (main.cpp): inputs must be regular files (a FIFO would hang the command, a device stream
// without end), outputs must be regular files or not exist, in a writable folder, and never one
// of the inputs under another name (same device and inode). The inputs are then protected for
// the whole run: every writer refuses them (atomic_output.hpp), also the files a command writes
// into an output folder.
#include <string>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus::cli {

struct CommandFiles {
  std::vector<std::string> inputs;         // files read (DEMs, a store, a keyframe path)
  std::vector<std::string> outputs;        // files written
  std::vector<std::string> outputFolders;  // folders written into (created when missing)
};

// Checks `files` as described above and protects the inputs. Errors name the file and why.
Status checkCommandFiles(const CommandFiles& files);

}  // namespace tellus::cli
