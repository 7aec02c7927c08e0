#include "dcshell/volume_loss.h"

#include <CGAL/Interval_nt.h>

#include <cmath>

#include "dcshell/mesh_volume.h"

namespace dcshell {

VolumeLoss volume_loss(const std::vector<ExactPolytope>& hulls, const std::vector<Mesh>& shells,
                       const std::vector<Overlap>* overlaps, double max_relative_error) {
  VolumeLoss out;
  CGAL::Mpzf six(0);
  for (const auto& s : shells) six += six_signed_volume(s);
  const ExactRational shells_exact = ExactRational(six) / 6;
  out.shells_volume = CGAL::to_double(shells_exact);
  out.union_stats = overlaps ? union_volume(hulls, *overlaps) : union_volume(hulls);
  out.union_volume = out.union_stats.value;

  using I = CGAL::Interval_nt<true>;  // protected: sets the rounding mode itself
  const I u(out.union_stats.value - out.union_stats.error_bound, out.union_stats.value + out.union_stats.error_bound);
  const auto sv = CGAL::to_interval(shells_exact);
  const I diff = u - I(sv.first, sv.second);
  if (u.inf() > 0) {
    const I loss = diff / u;
    const double width = loss.sup() - loss.inf();
    if (diff.inf() > 0 || diff.sup() < 0) {
      if (width <= max_relative_error * std::fabs(0.5 * (loss.inf() + loss.sup()))) {
        out.value = 0.5 * (loss.inf() + loss.sup());
        out.error_bound = 0.5 * width;
        return out;
      }
    }
  } else if (u.sup() <= 0) {
    return out;  // no union (no hulls): no loss to speak of
  }
  // The sign or the digits are undecided: everything exactly.
  const ExactRational u_exact = exact_union_volume(hulls, overlaps);
  out.union_volume = CGAL::to_double(u_exact);
  out.exact = true;
  if (CGAL::is_zero(u_exact)) return out;
  out.value = CGAL::to_double((u_exact - shells_exact) / u_exact);
  out.error_bound = std::fabs(out.value) * 1.2e-16;  // rounding of the exact rational
  return out;
}

}  // namespace dcshell
