#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <array>
#include <memory>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief The part of a convex polygon inside the unit square
     * (Sutherland–Hodgman, one half-plane after the other); empty if none.
     */
    std::vector<Point<2>>
    clip_to_unit_square(std::vector<Point<2>> polygon);

    /**
     * @brief The part of a convex polygon inside the reference triangle
     * (0,0), (1,0), (0,1); empty if none.
     */
    std::vector<Point<2>>
    clip_to_unit_triangle(std::vector<Point<2>> polygon);

    /** @brief Area of a simple polygon (shoelace formula), ≥ 0. */
    double
    polygon_area(const std::vector<Point<2>> &polygon);

    /**
     * @brief 3D segment integration (doc/formulation.md, "Two deformable
     * bodies"): the quadrature on a slave face, in its reference coordinates,
     * that integrates exactly the functions that are polynomial on each master
     * face's part of it.
     *
     * @param slave_corners the slave face's current corners: a quadrilateral's
     *   four in the lexicographic order of the reference face ((0,0), (1,0),
     *   (0,1), (1,1)), or a triangle's three ((0,0), (1,0), (0,1))
     * @param master_vertices the current corners of the nearby master faces,
     *   @p vertices_per_master_face per face in the same orders
     * @param n_points points per direction of the collapsed Gauss rule on each
     *   triangle of the segments (exact for degree 2 n − 2)
     *
     * Each master face is projected onto the slave face (closest point on the
     * bilinear quadrilateral or the flat triangle), clipped against the
     * reference square or triangle, and its part cut into triangles from its
     * first vertex. Returns null when one master face covers the slave face
     * (nothing to cut) or the parts do not tile it (the slave face leaves the
     * master surface, or the projected faces overlap by more than 1e-3 of the
     * face): then the face's own rule is used. Where the parts cover the face
     * to within 1e-3 (a curved master), the weights are scaled so that they
     * sum to the reference face's area.
     */
    std::shared_ptr<const Quadrature<2>>
    face_segments(const std::vector<Point<3>> &slave_corners,
                  const std::vector<Point<3>> &master_vertices,
                  unsigned int                 vertices_per_master_face,
                  unsigned int                 n_points);
  } // namespace Contact
} // namespace StabilizedLagrangian
