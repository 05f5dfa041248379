#pragma once
// Routes KHR_debug messages of the current context to the log and counts GL errors, so tests
// can fail on any GL error. installDebugOutput() needs a current debug context.
#include <cstdint>

namespace tellus::gl {

void installDebugOutput();

// Number of GL_DEBUG_TYPE_ERROR messages (and glGetError() codes seen by checkGlErrors()) so far,
// over all contexts of the process.
std::uint64_t glErrorCount();

// Drains glGetError(), logging and counting each code; returns how many there were.
int checkGlErrors(const char* where);

}  // namespace tellus::gl
