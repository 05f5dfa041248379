#pragma once
// Every read of GPU results by the CPU goes through here: glFinish, buffer and texture reads,
// query results, fence waits. Each call that makes (or may make) the calling thread wait for
// the GPU to catch up is counted, per thread, so that a frame loop can see what its renderer
// waited for: gpuWaitCount() before and after the frame (the bench's gpu_waits). A renderer's
// frame should make none: its results come back a frame or more late through fences, or stay
// on the GPU. Needs a current GL 4.5 context, except gpuWaitCount().
#include <cstddef>
#include <cstdint>

#include <epoxy/gl.h>

namespace tellus::gl {

// The calls of this thread so far that waited, or may have waited, for the GPU.
std::uint64_t gpuWaitCount();

// glFinish: always a wait.
void finish();

// glGetNamedBufferSubData: a wait (the driver first finishes every command writing the buffer).
void readBuffer(GLuint buffer, std::size_t offsetBytes, std::size_t bytes, void* out);

// glGetNamedBufferSubData of a buffer whose last write a fence has been seen to pass
// (Fence::passed()): no wait, not counted.
void readCompletedBuffer(GLuint buffer, std::size_t offsetBytes, std::size_t bytes, void* out);

// glGetTextureImage / glGetTextureSubImage (`bytes`: the size of `out`): a wait.
void readTextureImage(GLuint texture, GLint level, GLenum format, GLenum type, std::size_t bytes,
                      void* out);
void readTextureSubImage(GLuint texture, GLint level, GLint x, GLint y, GLint z, GLsizei width,
                         GLsizei height, GLsizei depth, GLenum format, GLenum type,
                         std::size_t bytes, void* out);

// A query's result (GL_QUERY_RESULT); a wait when it was not available yet.
std::uint64_t queryResult(GLuint query);

// glClientWaitSync; a wait when `timeoutNs` > 0 and the fence had not been signalled already
// (a timeout of 0 only asks).
GLenum clientWaitSync(GLsync sync, GLbitfield flags, GLuint64 timeoutNs);

}  // namespace tellus::gl
