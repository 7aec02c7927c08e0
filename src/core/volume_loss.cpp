#include "dcshell/volume_loss.h"

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

  // The loss 1 − S/U grows with U (S >= 0), so a union within [U − e, U + e] (U − e > 0) puts it
  // in [loss(U − e), loss(U + e)]: decided once that excludes 0 and is narrow enough.
  auto enclosure = [&](const ExactRational& u, double error_bound) -> std::pair<double, double> {
    const ExactRational e(error_bound), lo = u - e, hi = u + e;
    if (CGAL::sign(lo) <= 0) return {-HUGE_VAL, HUGE_VAL};
    return {CGAL::to_interval(ExactRational((lo - shells_exact) / lo)).first,
            CGAL::to_interval(ExactRational((hi - shells_exact) / hi)).second};
  };
  // The union itself to 1e-12, as union_volume gives it: the report prints it too.
  const UnionEnough enough = [&](const ExactRational& u, double error_bound) {
    const auto [l, h] = enclosure(u, error_bound);
    return (l > 0 || h < 0) && h - l <= max_relative_error * std::fabs(0.5 * (l + h)) &&
           2 * error_bound <= 1e-12 * CGAL::to_double(u);
  };
  // The union is refined only as far as the loss needs (intervals, fixed point, rationals).
  ExactRational u(0);
  out.union_stats = union_volume(hulls, overlaps, enough, UnionMethod::automatic, &u);
  out.union_volume = out.union_stats.value;
  if (CGAL::sign(u) <= 0) return out;  // no union (no hulls): no loss to speak of
  if (out.union_stats.exact_fallback) {  // the sign or the digits needed the exact union
    out.exact = true;
    out.value = CGAL::to_double(ExactRational((u - shells_exact) / u));
    out.error_bound = std::fabs(out.value) * 1.2e-16;  // rounding of the exact rational
    return out;
  }
  const auto [l, h] = enclosure(u, out.union_stats.error_bound);
  out.value = 0.5 * (l + h);
  out.error_bound = 0.5 * (h - l) * (1 + 0x1p-50) + std::fabs(out.value) * 0x1p-52;
  return out;
}

}  // namespace dcshell
