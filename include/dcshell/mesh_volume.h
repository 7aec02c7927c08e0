// Exact volume of a closed mesh as given by its double coordinates.
#pragma once
#include <CGAL/Bbox_3.h>
#include <CGAL/Mpzf.h>

#include "dcshell/kernel.h"

namespace dcshell {

/// 6 × the signed volume bounded by a closed, consistently oriented surface, exact on the
/// doubles: Mpzf (binary floating point of unbounded precision) holds sums and products of
/// doubles exactly, without the gcds a rational type would compute.
CGAL::Mpzf six_signed_volume(const Mesh& mesh);

/// The cube of a box's diagonal: the scale against which a part or shell of a set counts as
/// tiny (its volume below a fraction of it), the same for every reader of the set.
double diagonal_cube_volume(const CGAL::Bbox_3& box);

}  // namespace dcshell
