#pragma once
// ThreadSanitizer support for handing work to oneTBB.
//
// Debian's libtbb is not built with ThreadSanitizer, so TSan cannot see the synchronisation
// inside TBB's scheduler: the writes that build a task object on the submitting thread look
// unsynchronised with the worker that runs it, a false report on every task. Wrapping the
// submission in a TsanIgnoreWrites scope leaves those TBB-internal writes out of TSan's view;
// every access our own code makes, on either thread, is still checked. tsanHandOff() before the
// submission and tsanTakeOver() first thing in the task tell TSan about the happens-before
// edge that TBB's queue provides.
#if defined(__SANITIZE_THREAD__)
#define TELLUS_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define TELLUS_TSAN 1
#endif
#endif

#ifdef TELLUS_TSAN
extern "C" void AnnotateIgnoreWritesBegin(const char* file, int line);
extern "C" void AnnotateIgnoreWritesEnd(const char* file, int line);
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

namespace tellus {

struct TsanIgnoreWrites {
#ifdef TELLUS_TSAN
  TsanIgnoreWrites() {
    AnnotateIgnoreWritesBegin(__FILE__, __LINE__);
  }
  ~TsanIgnoreWrites() {
    AnnotateIgnoreWritesEnd(__FILE__, __LINE__);
  }
#endif
  TsanIgnoreWrites(const TsanIgnoreWrites&) = delete;
  TsanIgnoreWrites& operator=(const TsanIgnoreWrites&) = delete;
#ifndef TELLUS_TSAN
  TsanIgnoreWrites() = default;
#endif
};

inline void tsanHandOff([[maybe_unused]] void* token) {
#ifdef TELLUS_TSAN
  __tsan_release(token);
#endif
}
inline void tsanTakeOver([[maybe_unused]] void* token) {
#ifdef TELLUS_TSAN
  __tsan_acquire(token);
#endif
}

}  // namespace tellus
