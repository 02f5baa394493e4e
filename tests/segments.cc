// 3D segment integration (source/contact/segments.cc): a slave face cut along
// the master faces projected onto it integrates exactly the functions that are
// linear on each master face, where the face's own rule does not. Triangle and
// quadrilateral slave faces, against triangle and quadrilateral master faces
// (a flat patch 0.01 below the slave face, non-matching): the weights sum to
// the reference face's area, every point lies in the reference face, the
// polynomials of degree 2n − 2 integrate exactly, and so do |x − c| and
// |x + y − c| (|y − c| against quadrilaterals) whose kinks are master edges. The exact integrals
// come from the slave face cut by the kink's line in physical coordinates, written here
// independently of the code under test.

#include <deal.II/base/quadrature_lib.h>

#include <stabilized_lagrangian/contact/segments.h>

#include "check_tools.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace dealii;
using namespace StabilizedLagrangian;
using namespace CheckTools;

namespace
{
  using Polygon = std::vector<Point<2>>;

  /** ∫ over the polygon (counter-clockwise or not) of a·x + b: area × value at the centroid. */
  double
  integrate_linear(const Polygon &p, const Tensor<1, 2> &a, const double b)
  {
    double   area = 0.;
    Point<2> centroid;
    for (unsigned int i = 1; i + 1 < p.size(); ++i)
      {
        const double t = 0.5 * ((p[i][0] - p[0][0]) * (p[i + 1][1] - p[0][1]) -
                                (p[i + 1][0] - p[0][0]) * (p[i][1] - p[0][1]));
        area += t;
        centroid += t * (p[0] + p[i] + p[i + 1]) / 3.;
      }
    if (area == 0.)
      return 0.;
    centroid /= area;
    return std::abs(area) * (a * centroid + b);
  }

  /** The part of the polygon where a·x + b ≥ 0. */
  Polygon
  keep_positive(const Polygon &p, const Tensor<1, 2> &a, const double b)
  {
    Polygon kept;
    for (unsigned int i = 0; i < p.size(); ++i)
      {
        const Point<2> &u = p[i], &v = p[(i + 1) % p.size()];
        const double    fu = a * u + b, fv = a * v + b;
        if (fu >= 0.)
          kept.push_back(u);
        if ((fu >= 0.) != (fv >= 0.))
          kept.push_back(u + fu / (fu - fv) * (v - u));
      }
    return kept;
  }

  /** ∫ |a·x + b| over the polygon: its two sides of the line a·x + b = 0. */
  double
  integrate_kink(const Polygon &p, const Tensor<1, 2> &a, const double b)
  {
    return integrate_linear(keep_positive(p, a, b), a, b) +
           integrate_linear(keep_positive(p, -a, -b), -a, -b);
  }

  /**
   * The master patch: squares of side h on [−1, 3]², each split along the
   * diagonal x + y = const into two triangles (@p triangles), or whole; at
   * z = −0.01. Corners in the orders face_segments() reads.
   */
  std::vector<Point<3>>
  master_patch(const bool triangles, const double h)
  {
    std::vector<Point<3>> vertices;
    const auto            at = [](const double x, const double y) { return Point<3>(x, y, -0.01); };
    for (double x = -1.; x < 3. - 1e-12; x += h)
      for (double y = -1.; y < 3. - 1e-12; y += h)
        if (triangles)
          vertices.insert(vertices.end(),
                          {at(x, y),
                           at(x + h, y),
                           at(x, y + h), // below the diagonal
                           at(x + h, y + h),
                           at(x, y + h),
                           at(x + h, y)}); // above it
        else
          vertices.insert(vertices.end(), {at(x, y), at(x + h, y), at(x, y + h), at(x + h, y + h)});
    return vertices;
  }

  /** x(ξ) of the flat slave face with @p corners (3: triangle, 4: lexicographic quadrilateral). */
  Point<2>
  physical(const std::vector<Point<3>> &corners, const Point<2> &xi)
  {
    Point<3> x;
    if (corners.size() == 3)
      x = corners[0] + xi[0] * (corners[1] - corners[0]) + xi[1] * (corners[2] - corners[0]);
    else
      x = (1. - xi[0]) * (1. - xi[1]) * corners[0] + xi[0] * (1. - xi[1]) * corners[1] +
          (1. - xi[0]) * xi[1] * corners[2] + xi[0] * xi[1] * corners[3];
    return Point<2>(x[0], x[1]);
  }

  /** Σ w_q f(x(ξ_q)) |det J| for a flat parallelogram or triangle face. */
  double
  integrate(const Quadrature<2>                           &rule,
            const std::vector<Point<3>>                   &corners,
            const std::function<double(const Point<2> &)> &f)
  {
    const Tensor<1, 3> e0 = corners[1] - corners[0], e1 = corners[2] - corners[0];
    const double       jacobian = std::abs(e0[0] * e1[1] - e0[1] * e1[0]);
    double             sum      = 0.;
    for (unsigned int q = 0; q < rule.size(); ++q)
      sum += rule.weight(q) * f(physical(corners, rule.point(q))) * jacobian;
    return sum;
  }

  void
  test(const std::vector<Point<3>> &corners, const bool master_triangles, const std::string &name)
  {
    const bool         triangle = corners.size() == 3;
    const unsigned int n        = 3; // exact for degree 2n − 2 = 4 on each part
    const auto         master   = master_patch(master_triangles, 0.5);
    const auto         rule  = Contact::face_segments(corners, master, master_triangles ? 3 : 4, n);
    const std::string  label = name + (master_triangles ? " / triangles: " : " / quadrilaterals: ");
    check(rule != nullptr, label + "the face is cut (parts)", rule ? rule->size() : 0);
    if (!rule)
      return;
    const double reference_area = triangle ? 0.5 : 1.;
    double       sum = 0., outside = 0.;
    for (unsigned int q = 0; q < rule->size(); ++q)
      {
        const Point<2> &xi = rule->point(q);
        sum += rule->weight(q);
        outside = std::max({outside,
                            -xi[0],
                            -xi[1],
                            triangle ? xi[0] + xi[1] - 1. : xi[0] - 1.,
                            triangle ? 0. : xi[1] - 1.});
      }
    check_below(std::abs(sum - reference_area), 1e-13, label + "weights sum to the face's area");
    check_below(outside, 1e-13, label + "every point in the reference face (largest excess)");
    // ξ0^a ξ1^b up to degree 4: ∫_T = a! b! / (a + b + 2)!, ∫_square = 1 / ((a + 1)(b + 1))
    double worst = 0.;
    for (unsigned int a = 0; a <= 4; ++a)
      for (unsigned int b = 0; a + b <= 4; ++b)
        {
          double value = 0.;
          for (unsigned int q = 0; q < rule->size(); ++q)
            value +=
                rule->weight(q) * std::pow(rule->point(q)[0], a) * std::pow(rule->point(q)[1], b);
          const double exact =
              triangle ? std::tgamma(a + 1) * std::tgamma(b + 1) / std::tgamma(a + b + 3)
                       : 1. / ((a + 1.) * (b + 1.));
          worst = std::max(worst, std::abs(value - exact) / exact);
        }
    check_below(worst, 1e-12, label + "monomials of degree <= 4 exact (largest relative error)");
    // the kinks along master edges: x = 1, and x + y = 1.5 (the triangles' diagonals) or y = 1.5
    Polygon face;
    for (const unsigned int v :
         triangle ? std::vector<unsigned int>{0, 1, 2} : std::vector<unsigned int>{0, 1, 3, 2})
      face.push_back(Point<2>(corners[v][0], corners[v][1]));
    Tensor<1, 2> ex, second;
    ex[0]     = 1.;
    second[0] = master_triangles ? 1. : 0.;
    second[1] = 1.;
    for (const auto &[a, b, kink] :
         {std::make_tuple(ex, -1., std::string("|x - 1|")),
          std::make_tuple(
              second, -1.5, std::string(master_triangles ? "|x + y - 1.5|" : "|y - 1.5|"))})
      {
        const auto   f     = [a = a, b = b](const Point<2> &x) { return std::abs(a * x + b); };
        const double exact = integrate_kink(face, a, b);
        check_below(std::abs(integrate(*rule, corners, f) - exact) / exact,
                    1e-12,
                    label + kink + " exact on the segments (relative error)");
        // the face's own rule, not cut, is not exact: the test can tell
        const Quadrature<2> plain =
            triangle ? Quadrature<2>(QGaussSimplex<2>(n)) : Quadrature<2>(QGauss<2>(n));
        check(std::abs(integrate(plain, corners, f) - exact) / exact > 1e-6,
              label + kink + " with the face's own rule, relative error",
              std::abs(integrate(plain, corners, f) - exact) / exact);
      }
  }
} // namespace

int
main()
{
  // a triangle and a parallelogram, neither aligned with the master patch
  const std::vector<Point<3>> triangle = {
      Point<3>(0.1, 0.2, 0.), Point<3>(2.3, 0.4, 0.), Point<3>(0.7, 1.9, 0.)};
  const std::vector<Point<3>> parallelogram = {Point<3>(0.1, 0.2, 0.),
                                               Point<3>(2.1, 0.45, 0.),
                                               Point<3>(0.35, 1.7, 0.),
                                               Point<3>(2.35, 1.95, 0.)};
  for (const bool master_triangles : {true, false})
    {
      test(triangle, master_triangles, "triangle slave face");
      test(parallelogram, master_triangles, "quadrilateral slave face");
    }
  // one master face covering the slave face: nothing to cut
  const std::vector<Point<3>> big = {
      Point<3>(-5., -5., 0.), Point<3>(10., -5., 0.), Point<3>(-5., 10., 0.)};
  check(Contact::face_segments(triangle, big, 3, 3) == nullptr,
        "a triangle inside one master triangle is not cut",
        0.);
  return summary();
}
