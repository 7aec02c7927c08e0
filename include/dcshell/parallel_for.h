// Independent per-item work (one shell's remesh) on the machine's cores, with results that do
// not depend on the scheduling: each index writes only its own slot.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

namespace dcshell {

/// Calls f(i) once for every i in [0, n), on up to `threads` threads (0: the machine's cores).
/// f must touch only data of its own index (and shared data read-only). Items are taken in
/// index order; an exception thrown by f stops the handing out of further items, and the one of
/// the lowest index is rethrown once all threads have ended (so the error is the same however
/// the items were scheduled, as long as f throws for the same items).
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& f, unsigned threads = 0);

/// The items 0 .. n-1 by decreasing cost (ties by index), an order to hand them out in: with the
/// longest first, the short ones fill in at the end and no core waits on one long item started
/// last. Calling f(order[i]) for i in [0, n) keeps parallel_for's guarantees, the error reported
/// being the first failing item in that order.
std::vector<std::size_t> largest_first(const std::vector<double>& cost);

}  // namespace dcshell
