#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <stabilized_lagrangian/contact/segments.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    std::vector<Point<2>>
    clip_to_unit_square(std::vector<Point<2>> polygon)
    {
      for (unsigned int d = 0; d < 2; ++d)
        for (const double side : {0., 1.})
          {
            const auto inside = [d, side](const Point<2> &p) {
              return side == 0. ? p[d] >= 0. : p[d] <= 1.;
            };
            std::vector<Point<2>> kept;
            for (unsigned int i = 0; i < polygon.size(); ++i)
              {
                const Point<2> &a = polygon[i];
                const Point<2> &b = polygon[(i + 1) % polygon.size()];
                if (inside(a))
                  kept.push_back(a);
                if (inside(a) != inside(b))
                  kept.push_back(a + (side - a[d]) / (b[d] - a[d]) * (b - a));
              }
            polygon = kept;
          }
      return polygon;
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
    face_segments(const std::array<Point<3>, 4> &slave_corners,
                  const std::vector<Point<3>>   &master_vertices,
                  const unsigned int             n_points)
    {
      const double diameter = std::max(slave_corners[0].distance(slave_corners[3]),
                                       slave_corners[1].distance(slave_corners[2]));
      std::vector<std::vector<Point<2>>> parts;
      double                             covered = 0.;
      for (unsigned int f = 0; f + 4 <= master_vertices.size(); f += 4)
        {
          // the face's corners around its boundary: (0,0), (1,0), (1,1), (0,1)
          std::vector<Point<2>> polygon;
          bool                  near = true;
          for (const unsigned int v : {0u, 1u, 3u, 2u})
            {
              const auto [xi, distance] = project(slave_corners, master_vertices[f + v]);
              near                      = near && distance <= diameter;
              polygon.push_back(xi);
            }
          if (!near)
            continue;
          polygon           = clip_to_unit_square(polygon);
          const double area = polygon_area(polygon);
          if (polygon.size() < 3 || area < 1e-12)
            continue;
          parts.push_back(polygon);
          covered += area;
        }
      if (parts.size() < 2 || std::abs(covered - 1.) > 1e-3)
        return nullptr;
      const QGauss<1>       gauss(n_points);
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (const auto &part : parts)
        for (unsigned int k = 1; k + 1 < part.size(); ++k)
          add_triangle(part[0], part[k], part[k + 1], gauss, points, weights);
      for (double &w : weights)
        w /= covered;
      return std::make_shared<const Quadrature<2>>(points, weights);
    }
  } // namespace Contact
} // namespace StabilizedLagrangian
