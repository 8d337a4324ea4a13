// The device check (preset cpu-devcheck): a CPU build in which execution-space memory
// behaves like GPU memory seen from the host. Every Buffer is mapped on its own pages,
// inaccessible while no parallel loop, reduction, algo call or upload/download runs, so
// host code that reads or writes it directly (the bug that crashes the CUDA build)
// stops at once with a message naming the buffer, instead of passing every CPU test.
// Without SURGE_DEVCHECK, Open is an empty type and nothing here costs anything.
#pragma once
#include <cstddef>

namespace surge::par::devcheck {

#if defined(SURGE_DEVCHECK)
// Page-mapped memory for one buffer, inaccessible unless an Open is alive.
void* allocate(std::size_t bytes);
void release(void* p, std::size_t bytes);
// Makes every buffer accessible; nested scopes count, the outermost one closes.
void open();
void close();
// Whether buffers are accessible now (tests of the check itself).
bool is_open();
struct Open {
  Open() { open(); }
  ~Open() { close(); }
  Open(const Open&) = delete;
  Open& operator=(const Open&) = delete;
};
#else
struct Open {
  Open() {}  // NOLINT(modernize-use-equals-default): user-provided, so call sites see no
  ~Open() {} // NOLINT(modernize-use-equals-default): unused-variable warning
  Open(const Open&) = delete;
  Open& operator=(const Open&) = delete;
};
inline bool is_open() { return true; }
#endif

} // namespace surge::par::devcheck
