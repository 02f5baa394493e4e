#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <string>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    using namespace dealii;

    /**
     * @brief The steps the built-in geometries (source/geometry/scene.cc)
     * share to build their meshes.
     */
    namespace MeshBuilding
    {
      /** Refine @p steps times the cells whose centre lies within @p radius of @p center. */
      template <int dim>
      void
      refine_near(Triangulation<dim> &triangulation,
                  const Point<dim>   &center,
                  const double        radius,
                  const unsigned int  steps);

      /** Declare `Cell shape`: hypercubes, or each cell split into simplices. */
      void
      declare_cell_shape(ParameterHandler &prm);

      /** Whether `Cell shape` asks for simplices; refuse what they cannot do. */
      template <int dim>
      bool
      read_cell_shape(const ParameterHandler &prm,
                      const std::string      &section,
                      const bool              local_refinement);

      /**
       * Replace the uniformly refined hypercube mesh @p triangulation (serial)
       * by its split into simplices, keeping boundary and material ids.
       */
      template <int dim>
      void
      split_into_simplices(Triangulation<dim> &triangulation);

      /**
       * In 3D, the children of a refined face all join the contact zone
       * (boundary id @p zone) when one of them is in it: where the zone ended
       * inside a refined face, a hanging vertex of Γc would be constrained to
       * a vertex off Γc, which has no multiplier. (In 2D the boundary has no
       * hanging vertices.)
       */
      template <int dim>
      void
      close_contact_zone(Triangulation<dim> &triangulation, const types::boundary_id zone);

      /**
       * Turn deal.II's quarter ball (the orthant x_i >= 0 of a ball about the
       * origin) below its centre by a rotation, (x, y) -> (y, -x) and (x, y, z)
       * -> (y, x, -z), and move the centre to @p center.
       */
      template <int dim>
      void
      turn_orthant_below(Triangulation<dim> &triangulation, const Point<dim> &center);

      /** The ball parameters shared by `half ball` and `two balls`. */
      void
      declare_ball_parameters(ParameterHandler &prm, const std::string &radius_documentation);

      /**
       * `Contact zone radius` of the ball @p section of radius @p radius:
       * in (0, 2 R], 2 R taking the whole curved side (a radius of no face
       * was reported as the contact surface's missing boundary id).
       */
      double
      contact_zone_radius(const ParameterHandler &prm, const std::string &section, double radius);
    } // namespace MeshBuilding
  }   // namespace Geometry
} // namespace StabilizedLagrangian
