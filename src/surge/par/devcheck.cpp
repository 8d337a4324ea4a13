#include "surge/par/devcheck.hpp"

#if defined(SURGE_DEVCHECK)
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <map>
#include <mutex>
#include <new>
#include <sys/mman.h>
#include <unistd.h>

namespace surge::par::devcheck {
namespace {

// All buffers come from one reserved range, so opening or closing access is a single
// mprotect over [base, base + top) however many buffers are alive (a DEM step opens
// and closes it tens of times).
constexpr std::size_t reserve_bytes = std::size_t{256} << 30; // address space only

struct Registry {
  std::mutex m;
  char* base = nullptr;
  std::size_t top = 0;                     // bytes of the range handed out so far
  std::map<std::size_t, std::size_t> live; // offset -> bytes, for the fault message
  std::map<std::size_t, std::size_t> free; // offset -> bytes, coalesced
  int depth = 0;
};
Registry& registry() {
  static Registry* r = new Registry; // never destroyed: buffers may outlive static destructors
  return *r;
}

std::size_t page_round(std::size_t bytes) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return (bytes == 0 ? page : (bytes + page - 1) / page * page);
}

// The cost of mprotect grows with the pages it changes: on 2 MiB transparent huge pages
// it is ~100 times smaller than on 4 KiB ones (6 us instead of 600 us for 16 MiB), so the
// range is huge-page aligned and toggled in whole huge pages.
constexpr std::size_t huge_page = std::size_t{2} << 20;

void set_access(Registry& r, int prot) {
  const std::size_t span = (r.top + huge_page - 1) / huge_page * huge_page;
  if (span > 0 && mprotect(r.base, span, prot) != 0) std::abort();
}

// A fault inside the range is host code touching execution-space memory: say so and
// abort. Any other fault goes to the default handler (a plain crash).
void on_fault(int sig, siginfo_t* info, void*) {
  auto* a = static_cast<char*>(info->si_addr);
  Registry& r = registry();
  if (r.base && a >= r.base && a < r.base + reserve_bytes) {
    const auto off = static_cast<std::size_t>(a - r.base);
    std::size_t start = 0, bytes = 0;
    auto it = r.live.upper_bound(off);
    if (it != r.live.begin()) {
      --it;
      start = it->first;
      bytes = it->second;
    }
    char msg[320];
    const int len = std::snprintf(msg, sizeof msg,
                                  "surge devcheck: host code touched execution-space memory at %p (byte %zu of a "
                                  "%zu-byte buffer) outside a parallel loop, algo call or upload/download: in the "
                                  "CUDA build this is a host access to GPU memory\n",
                                  static_cast<void*>(a), off - start, bytes);
    if (len > 0) (void)!write(2, msg, static_cast<std::size_t>(len));
    std::abort();
  }
  std::signal(sig, SIG_DFL);
}

void init(Registry& r) {
  if (r.base) return;
  void* p = mmap(nullptr, reserve_bytes + huge_page, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  const auto addr = reinterpret_cast<std::uintptr_t>(p);
  r.base = reinterpret_cast<char*>((addr + huge_page - 1) / huge_page * huge_page);
  madvise(r.base, reserve_bytes, MADV_HUGEPAGE); // a hint; without huge pages only slower
  struct sigaction sa {};
  sa.sa_sigaction = on_fault;
  sa.sa_flags = SA_SIGINFO;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGSEGV, &sa, nullptr);
  sigaction(SIGBUS, &sa, nullptr);
}

} // namespace

void* allocate(std::size_t bytes) {
  Registry& r = registry();
  const std::lock_guard lock(r.m);
  init(r);
  const std::size_t n = page_round(bytes);
  std::size_t off = r.top;
  auto it = r.free.begin();
  while (it != r.free.end() && it->second < n) ++it;
  if (it != r.free.end()) { // first fit
    off = it->first;
    const std::size_t rest = it->second - n;
    r.free.erase(it);
    if (rest > 0) r.free.emplace(off + n, rest);
  } else {
    if (r.top + n > reserve_bytes) throw std::bad_alloc();
    r.top += n;
  }
  r.live.emplace(off, n);
  if (r.depth > 0 && mprotect(r.base + off, n, PROT_READ | PROT_WRITE) != 0) std::abort();
  return r.base + off;
}

void release(void* p, std::size_t /*bytes*/) {
  Registry& r = registry();
  const std::lock_guard lock(r.m);
  std::size_t off = static_cast<std::size_t>(static_cast<char*>(p) - r.base);
  auto it = r.live.find(off);
  if (it == r.live.end()) std::abort();
  std::size_t n = it->second;
  r.live.erase(it);
  madvise(r.base + off, n, MADV_DONTNEED); // give the pages back; the range stays reserved
  auto next = r.free.lower_bound(off);
  if (next != r.free.end() && next->first == off + n) { // merge with the block after
    n += next->second;
    next = r.free.erase(next);
  }
  if (next != r.free.begin()) { // and with the block before
    auto prev = std::prev(next);
    if (prev->first + prev->second == off) {
      off = prev->first;
      n += prev->second;
      r.free.erase(prev);
    }
  }
  if (off + n == r.top) {
    if (mprotect(r.base + off, n, PROT_NONE) != 0) std::abort();
    r.top = off;
  } else {
    r.free.emplace(off, n);
  }
}

void open() {
  Registry& r = registry();
  const std::lock_guard lock(r.m);
  if (r.depth++ == 0) set_access(r, PROT_READ | PROT_WRITE);
}

void close() {
  Registry& r = registry();
  const std::lock_guard lock(r.m);
  if (--r.depth == 0) set_access(r, PROT_NONE);
}

bool is_open() {
  Registry& r = registry();
  const std::lock_guard lock(r.m);
  return r.depth > 0;
}

} // namespace surge::par::devcheck
#endif
