// Independent per-item work (one shell's remesh) on the machine's cores, with results that do
// not depend on the scheduling: each index writes only its own slot.
#pragma once
#include <cstddef>
#include <functional>

namespace dcshell {

/// Calls f(i) once for every i in [0, n), on up to `threads` threads (0: the machine's cores).
/// f must touch only data of its own index (and shared data read-only). Items are taken in
/// index order; an exception thrown by f stops the handing out of further items, and the one of
/// the lowest index is rethrown once all threads have ended (so the error is the same however
/// the items were scheduled, as long as f throws for the same items).
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& f, unsigned threads = 0);

}  // namespace dcshell
