#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <stabilized_lagrangian/contact/segments.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    namespace
    {
      /**
       * The part of a convex polygon where a·ξ ≤ b for every half-plane (a, b)
       * of @p half_planes (Sutherland–Hodgman, one half-plane after the other).
       */
      std::vector<Point<2>>
      clip(std::vector<Point<2>>                               polygon,
           const std::vector<std::pair<Tensor<1, 2>, double>> &half_planes)
      {
        for (const auto &[a, b] : half_planes)
          {
            const auto            excess = [&a = a, b = b](const Point<2> &p) { return a * p - b; };
            std::vector<Point<2>> kept;
            for (unsigned int i = 0; i < polygon.size(); ++i)
              {
                const Point<2> &p = polygon[i];
                const Point<2> &q = polygon[(i + 1) % polygon.size()];
                if (excess(p) <= 0.)
                  kept.push_back(p);
                if ((excess(p) <= 0.) != (excess(q) <= 0.))
                  kept.push_back(p + excess(p) / (excess(p) - excess(q)) * (q - p));
              }
            polygon = kept;
          }
        return polygon;
      }
    } // namespace

    std::vector<Point<2>>
    clip_to_unit_square(std::vector<Point<2>> polygon)
    {
      return clip(std::move(polygon),
                  {{Tensor<1, 2>({-1., 0.}), 0.},
                   {Tensor<1, 2>({1., 0.}), 1.},
                   {Tensor<1, 2>({0., -1.}), 0.},
                   {Tensor<1, 2>({0., 1.}), 1.}});
    }

    std::vector<Point<2>>
    clip_to_unit_triangle(std::vector<Point<2>> polygon)
    {
      return clip(std::move(polygon),
                  {{Tensor<1, 2>({-1., 0.}), 0.},
                   {Tensor<1, 2>({0., -1.}), 0.},
                   {Tensor<1, 2>({1., 1.}), 1.}});
    }

    double
    polygon_area(const std::vector<Point<2>> &polygon)
    {
      double twice = 0.;
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &a = polygon[i];
          const Point<2> &b = polygon[(i + 1) % polygon.size()];
          twice += a[0] * b[1] - a[1] * b[0];
        }
      return 0.5 * std::abs(twice);
    }

    namespace
    {
      /** x(ξ) on the bilinear face through @p c (lexicographic) and ∂x/∂ξ. */
      Point<3>
      bilinear(const std::array<Point<3>, 4> &c, const Point<2> &xi, Tensor<1, 3> (&dx)[2])
      {
        const double s = xi[0], t = xi[1];
        dx[0] = (1. - t) * (c[1] - c[0]) + t * (c[3] - c[2]);
        dx[1] = (1. - s) * (c[2] - c[0]) + s * (c[3] - c[1]);
        return Point<3>((1. - s) * (1. - t) * c[0] + s * (1. - t) * c[1] + (1. - s) * t * c[2] +
                        s * t * c[3]);
      }

      /**
       * The reference point of the closest point of the bilinear face to @p p
       * (Gauss–Newton on the face's plane of tangents, one step when the face
       * is a parallelogram), and the distance.
       */
      std::pair<Point<2>, double>
      project(const std::array<Point<3>, 4> &corners, const Point<3> &p)
      {
        Point<2>     xi(0.5, 0.5);
        Tensor<1, 3> dx[2];
        for (unsigned int iteration = 0; iteration < 20; ++iteration)
          {
            const Tensor<1, 3> r = p - bilinear(corners, xi, dx);
            Tensor<2, 2>       normal_matrix;
            Tensor<1, 2>       rhs;
            for (unsigned int a = 0; a < 2; ++a)
              {
                rhs[a] = dx[a] * r;
                for (unsigned int b = 0; b < 2; ++b)
                  normal_matrix[a][b] = dx[a] * dx[b];
              }
            const Tensor<1, 2> step = invert(normal_matrix) * rhs;
            xi += step;
            if (step.norm() < 1e-14)
              break;
          }
        return {xi, p.distance(bilinear(corners, xi, dx))};
      }

      /**
       * The reference point of the closest point of the slave face with
       * corners @p corners to @p p, and the distance: the bilinear
       * quadrilateral (four corners, lexicographic) or the flat triangle
       * (three corners: (0,0), (1,0), (0,1)), whose affine map is inverted in
       * one step.
       */
      std::pair<Point<2>, double>
      project_on_face(const std::vector<Point<3>> &corners, const Point<3> &p)
      {
        if (corners.size() == 4)
          return project({{corners[0], corners[1], corners[2], corners[3]}}, p);
        const Tensor<1, 3> e[2] = {corners[1] - corners[0], corners[2] - corners[0]};
        Tensor<2, 2>       normal_matrix;
        Tensor<1, 2>       rhs;
        for (unsigned int a = 0; a < 2; ++a)
          {
            rhs[a] = e[a] * (p - corners[0]);
            for (unsigned int b = 0; b < 2; ++b)
              normal_matrix[a][b] = e[a] * e[b];
          }
        const Point<2> xi(invert(normal_matrix) * rhs);
        return {xi, p.distance(corners[0] + xi[0] * e[0] + xi[1] * e[1])};
      }

      /** A collapsed (Duffy) Gauss rule on the triangle a, b, c, appended. */
      void
      add_triangle(const Point<2>        &a,
                   const Point<2>        &b,
                   const Point<2>        &c,
                   const QGauss<1>       &gauss,
                   std::vector<Point<2>> &points,
                   std::vector<double>   &weights)
      {
        const Tensor<1, 2> ab = b - a, ac = c - a, bc = c - b;
        const double       twice_area = std::abs(ab[0] * ac[1] - ab[1] * ac[0]);
        for (unsigned int i = 0; i < gauss.size(); ++i)
          for (unsigned int j = 0; j < gauss.size(); ++j)
            {
              const double u = gauss.point(i)[0], v = gauss.point(j)[0];
              points.push_back(a + u * (ab + v * bc));
              weights.push_back(gauss.weight(i) * gauss.weight(j) * u * twice_area);
            }
      }
    } // namespace

    std::shared_ptr<const Quadrature<2>>
    face_segments(const std::vector<Point<3>> &slave_corners,
                  const std::vector<Point<3>> &master_vertices,
                  const unsigned int           vertices_per_master_face,
                  const unsigned int           n_points)
    {
      Assert(slave_corners.size() == 3 || slave_corners.size() == 4, ExcInternalError());
      const bool triangle = slave_corners.size() == 3;
      if (vertices_per_master_face < 3)
        return nullptr;
      // the face's area in its reference coordinates, and its size
      const double reference_area = triangle ? 0.5 : 1.;
      double       diameter       = 0.;
      for (const auto &a : slave_corners)
        for (const auto &b : slave_corners)
          diameter = std::max(diameter, a.distance(b));
      // a master face's corners around its boundary: (0,0), (1,0), (1,1), (0,1), or the triangle's
      const std::vector<unsigned int>    around = vertices_per_master_face == 4
                                                      ? std::vector<unsigned int>{0, 1, 3, 2}
                                                      : std::vector<unsigned int>{0, 1, 2};
      std::vector<std::vector<Point<2>>> parts;
      double                             covered = 0.;
      for (unsigned int f = 0; f + vertices_per_master_face <= master_vertices.size();
           f += vertices_per_master_face)
        {
          std::vector<Point<2>> polygon;
          bool                  near = true;
          for (const unsigned int v : around)
            {
              const auto [xi, distance] = project_on_face(slave_corners, master_vertices[f + v]);
              near                      = near && distance <= diameter;
              polygon.push_back(xi);
            }
          if (!near)
            continue;
          polygon = triangle ? clip_to_unit_triangle(polygon) : clip_to_unit_square(polygon);
          const double area = polygon_area(polygon);
          if (polygon.size() < 3 || area < 1e-12 * reference_area)
            continue;
          parts.push_back(polygon);
          covered += area;
        }
      if (parts.size() < 2 || std::abs(covered - reference_area) > 1e-3 * reference_area)
        return nullptr;
      const QGauss<1>       gauss(n_points);
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (const auto &part : parts)
        for (unsigned int k = 1; k + 1 < part.size(); ++k)
          add_triangle(part[0], part[k], part[k + 1], gauss, points, weights);
      for (double &w : weights)
        w *= reference_area / covered;
      return std::make_shared<const Quadrature<2>>(points, weights);
    }
  } // namespace Contact
} // namespace StabilizedLagrangian
