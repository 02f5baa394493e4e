// The steps the built-in geometries (source/geometry/scene.cc) share to
// build their meshes: local refinement, the split into simplices, the
// closing of a 3D contact zone, the ball's placement and parameters.

#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <stabilized_lagrangian/geometry/mesh_building.h>
#include <stabilized_lagrangian/plugins.h>

#include <functional>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    namespace MeshBuilding
    {
      template <int dim>
      void
      refine_near(Triangulation<dim> &triangulation,
                  const Point<dim>   &center,
                  const double        radius,
                  const unsigned int  steps)
      {
        for (unsigned int step = 0; step < steps; ++step)
          {
            for (const auto &cell : triangulation.active_cell_iterators())
              if (cell->is_locally_owned() && cell->center().distance(center) < radius)
                cell->set_refine_flag();
            triangulation.execute_coarsening_and_refinement();
          }
      }

      void
      declare_cell_shape(ParameterHandler &prm)
      {
        prm.declare_entry(
            "Cell shape",
            "hypercube",
            Patterns::Selection("hypercube|simplex"),
            "hypercube: quadrilaterals (2D) or hexahedra (3D). simplex: each cell of the "
            "uniformly refined mesh split into 8 triangles (2D) or 24 tetrahedra (3D); the "
            "local refinements then refine the simplices (2D only: deal.II 9.4 has no "
            "hanging-node constraints on tetrahedra). Simplex meshes need a P pair "
            "(Contact/Finite element pair = P1/P1, P2/P1, P2/P2, P1/P2).");
      }

      template <int dim>
      bool
      read_cell_shape(const ParameterHandler &prm,
                      const std::string      &section,
                      const bool              local_refinement)
      {
        const bool simplex = prm.get("Cell shape") == "simplex";
        if (simplex && dim == 3 && local_refinement)
          throw InputError(section +
                           "/Local refinements must be 0 with Cell shape = simplex in 3D: "
                           "deal.II 9.4 cannot constrain the hanging nodes of tetrahedra. "
                           "Refine uniformly (Global refinements) instead.");
        return simplex;
      }

      template <int dim>
      void
      split_into_simplices(Triangulation<dim> &triangulation)
      {
        // the manifolds place the new vertices (edge and face midpoints) on curved boundaries
        Triangulation<dim> flat;
        GridGenerator::flatten_triangulation(triangulation, flat);
        for (const auto id : triangulation.get_manifold_ids())
          if (id != numbers::flat_manifold_id)
            flat.set_manifold(id, triangulation.get_manifold(id));
        triangulation.clear();
        GridGenerator::convert_hypercube_to_simplex_mesh(flat, triangulation);
        for (const auto id : flat.get_manifold_ids())
          if (id != numbers::flat_manifold_id)
            triangulation.set_manifold(id, flat.get_manifold(id));
      }

      template <int dim>
      void
      close_contact_zone(Triangulation<dim> &triangulation, const types::boundary_id zone)
      {
        const std::function<void(const typename Triangulation<dim>::face_iterator &)> join =
            [&join, zone](const typename Triangulation<dim>::face_iterator &face) {
              face->set_boundary_id(zone);
              if (face->has_children())
                for (unsigned int c = 0; c < face->n_children(); ++c)
                  join(face->child(c));
            };
        // (not from the artificial cells of a distributed mesh: they stand coarser
        // than the mesh is there, and their faces would pull in faces of the zone's
        // neighbours that lie outside it)
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->level() > 0 && !cell->is_artificial())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == zone)
                join(cell->parent()->face(f));
      }

      template <int dim>
      void
      turn_orthant_below(Triangulation<dim> &triangulation, const Point<dim> &center)
      {
        GridTools::transform(
            [&](const Point<dim> &p) {
              Point<dim> q;
              q[0] = p[1];
              if (dim == 2)
                q[1] = -p[0];
              else
                {
                  q[1]       = p[0];
                  q[dim - 1] = -p[dim - 1];
                }
              return q + center;
            },
            triangulation);
      }

      void
      declare_ball_parameters(ParameterHandler &prm, const std::string &radius_documentation)
      {
        prm.declare_entry("Radius", "100", Patterns::Double(), "Radius R (mm), > 0.");
        prm.declare_entry(
            "Global refinements", "3", Patterns::Integer(0, 12), "Uniform refinements.");
        prm.declare_entry("Local refinements",
                          "3",
                          Patterns::Integer(0, 12),
                          "Refinements of the cells within `Local refinement radius` of the "
                          "contact point, after the uniform ones.");
        prm.declare_entry(
            "Local refinement radius", "30", Patterns::Double(), radius_documentation);
        prm.declare_entry("Contact zone radius",
                          "20",
                          Patterns::Double(),
                          "Curved faces within this distance (mm) of the contact point form "
                          "the candidate contact surface. When it is larger than the "
                          "local refinement radius, the contact mesh has hanging nodes.");
      }

      double
      contact_zone_radius(const ParameterHandler &prm, const std::string &section, double radius)
      {
        const double zone = prm.get_double("Contact zone radius");
        // (a radius <= 0 is refused with its own entry)
        if (radius > 0. && !(zone > 0. && zone <= 2. * radius))
          throw InputError(section + "/Contact zone radius = " + prm.get("Contact zone radius") +
                           ": the distance (mm) from the contact point within which the curved "
                           "faces form the contact surface must be > 0 and at most twice the "
                           "radius, " +
                           Utilities::to_string(2. * radius) + " (the whole curved side).");
        return zone;
      }

      template void
      refine_near(Triangulation<2> &, const Point<2> &, double, unsigned int);
      template void
      refine_near(Triangulation<3> &, const Point<3> &, double, unsigned int);
      template bool
      read_cell_shape<2>(const ParameterHandler &, const std::string &, bool);
      template bool
      read_cell_shape<3>(const ParameterHandler &, const std::string &, bool);
      template void
      split_into_simplices(Triangulation<2> &);
      template void
      split_into_simplices(Triangulation<3> &);
      template void
      close_contact_zone(Triangulation<2> &, types::boundary_id);
      template void
      close_contact_zone(Triangulation<3> &, types::boundary_id);
      template void
      turn_orthant_below(Triangulation<2> &, const Point<2> &);
      template void
      turn_orthant_below(Triangulation<3> &, const Point<3> &);
    } // namespace MeshBuilding
  }   // namespace Geometry
} // namespace StabilizedLagrangian
