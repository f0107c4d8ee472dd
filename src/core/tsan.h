#pragma once
/// What a ThreadSanitizer build (make test-tsan) needs to know and to say. Debian builds its
/// libraries without TSan, so TSan cannot see how they synchronise: where one of them orders
/// accesses of ours (a reference count, a queue between its threads), the code says so here with
/// a release on the handing side and an acquire on the taking side. Both are no-ops elsewhere.

#if defined(__SANITIZE_THREAD__)
#define RESCUESIM_UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define RESCUESIM_UNDER_TSAN 1
#endif
#endif

#if defined(RESCUESIM_UNDER_TSAN)
#include <sanitizer/tsan_interface.h>
// exported by libtsan, not declared by GCC 12's tsan_interface.h
extern "C" void __tsan_ignore_thread_begin();
extern "C" void __tsan_ignore_thread_end();
#endif

namespace rescuesim {

#if defined(RESCUESIM_UNDER_TSAN)
inline constexpr bool kUnderTsan = true;
#else
inline constexpr bool kUnderTsan = false;
#endif

/// Everything this thread did so far happens before what a thread does after a later
/// tsan_acquire of the same address.
inline void tsan_release([[maybe_unused]] const void* address) {
#if defined(RESCUESIM_UNDER_TSAN)
  __tsan_release(const_cast<void*>(address));
#endif
}

/// What threads did before their tsan_release of this address happens before what this thread
/// does next.
inline void tsan_acquire([[maybe_unused]] const void* address) {
#if defined(RESCUESIM_UNDER_TSAN)
  __tsan_acquire(const_cast<void*>(address));
#endif
}

/// Within its scope TSan does not check this thread's reads and writes; its locks and the
/// annotations above still count. For a library's own bookkeeping that its header inlines into
/// our code (a reference count it orders with atomics elsewhere uninstrumented), never for data
/// of ours.
class TsanIgnoreAccesses {
 public:
  TsanIgnoreAccesses() {  // NOLINT(modernize-use-equals-default): empty only outside TSan
#if defined(RESCUESIM_UNDER_TSAN)
    __tsan_ignore_thread_begin();
#endif
  }
  ~TsanIgnoreAccesses() {  // NOLINT(modernize-use-equals-default): empty only outside TSan
#if defined(RESCUESIM_UNDER_TSAN)
    __tsan_ignore_thread_end();
#endif
  }
  TsanIgnoreAccesses(const TsanIgnoreAccesses&) = delete;
  TsanIgnoreAccesses& operator=(const TsanIgnoreAccesses&) = delete;
};

}  // namespace rescuesim
