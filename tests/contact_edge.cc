// The square-root onset of the pressure estimate (source/contact/contact_edge.cc):
// fitted to the points of a face crossed by the edge of the contact zone,
// with the pressure c √d inside and the gap (4c/3E*) (−d)^{3/2} outside, it
// finds the edge and c exactly, 2D and 3D (an edge oblique to the face);
// faces entirely in contact or entirely open have no fit; a gap too large
// for the pressure (an edge outside the face) is not taken for one.

#include <stabilized_lagrangian/contact/contact_edge.h>

#include "check_tools.h"

#include <cmath>
#include <cstdlib>
#include <string>

using namespace dealii;
using namespace StabilizedLagrangian;
using namespace CheckTools;

namespace
{
  /**
   * The fit to the exact field of an edge through @p edge_point with unit
   * normal @p direction (towards the contact zone) at @p points; the largest
   * error of the fitted pressure at @p probes.
   */
  template <int dim>
  double
  fit_error(const std::vector<Point<dim>> &points,
            const std::vector<Point<dim>> &probes,
            const Point<dim>              &edge_point,
            const Tensor<1, dim>          &direction,
            bool                          &valid)
  {
    const double   c = 3000., modulus = 200000. / 0.91;
    Tensor<1, dim> normal;
    normal[dim - 1] = -1.;
    std::vector<bool>   in_contact;
    std::vector<double> pressures, gaps;
    for (const auto &x : points)
      {
        const double d = (x - edge_point) * direction;
        in_contact.push_back(d > 0.);
        pressures.push_back(d > 0. ? c * std::sqrt(d) : 0.);
        gaps.push_back(d > 0. ? 0. : 4. * c / (3. * modulus) * std::pow(-d, 1.5));
      }
    const Contact::SquareRootOnset<dim> onset(points, in_contact, pressures, gaps, normal, modulus);
    valid        = onset.valid();
    double error = 0.;
    if (valid)
      for (const auto &x : probes)
        error = std::max(error,
                         std::abs(onset.pressure(x) -
                                  c * std::sqrt(std::max((x - edge_point) * direction, 0.))) /
                             c);
    return error;
  }
} // namespace

int
main()
{
  bool valid = false;
  {
    // a 2D face [0, 0.5] with its two nodes, the edge at 0.3
    const std::vector<Point<2>> nodes{Point<2>(0., 0.), Point<2>(0.5, 0.)};
    std::vector<Point<2>>       probes;
    for (unsigned int i = 0; i <= 20; ++i)
      probes.emplace_back(0.5 * i / 20., 0.);
    // beside the edge the pressure is √d: a round-off of 1e-14 in d shows as
    // 1e-7 of c, so the tolerance is 1e-5 (a wrong exponent would be off by 0.1)
    double e = fit_error<2>(nodes, probes, Point<2>(0.3, 0.), Tensor<1, 2>({-1., 0.}), valid);
    check(
        valid && e < 1e-5, "2D: the edge and c found from one pressure and one gap, error / c", e);
    // three nodes (a quadratic face), the edge near its far end
    const std::vector<Point<2>> three{Point<2>(0., 0.), Point<2>(0.25, 0.), Point<2>(0.5, 0.)};
    e = fit_error<2>(three, probes, Point<2>(0.45, 0.), Tensor<1, 2>({-1., 0.}), valid);
    check(valid && e < 1e-5, "2D, three points: the edge near the open end, error / c", e);
    fit_error<2>(nodes, probes, Point<2>(0.7, 0.), Tensor<1, 2>({-1., 0.}), valid);
    check(!valid, "2D: a face entirely in contact has no fit", valid);
  }
  {
    // a 3D face [0, 1]² with its four nodes, an oblique edge that leaves
    // one node open
    const std::vector<Point<3>> nodes{
        Point<3>(0., 0., 0.), Point<3>(1., 0., 0.), Point<3>(0., 1., 0.), Point<3>(1., 1., 0.)};
    std::vector<Point<3>> probes;
    for (unsigned int i = 0; i <= 10; ++i)
      for (unsigned int j = 0; j <= 10; ++j)
        probes.emplace_back(0.1 * i, 0.1 * j, 0.);
    Tensor<1, 3> direction({-1., -0.5, 0.});
    direction /= direction.norm();
    // the edge through (0.8, 0.9): nodes (0,0), (1,0), (0,1) in contact, (1,1) open;
    // four points, three unknowns: the fit is exact where the edge is straight
    double e = fit_error<3>(nodes, probes, Point<3>(0.8, 0.9, 0.), direction, valid);
    check(valid && e < 1e-5, "3D: an oblique straight edge found from four nodes, error / c", e);
    fit_error<3>(nodes, probes, Point<3>(-0.5, 0., 0.), Tensor<1, 3>({-1., 0., 0.}), valid);
    check(!valid, "3D: a face entirely open has no fit", valid);
  }
  return summary();
}
