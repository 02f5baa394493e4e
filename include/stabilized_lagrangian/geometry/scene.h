#pragma once

#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/geometry/size_estimate.h>
#include <stabilized_lagrangian/plugins.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    using namespace dealii;

    /**
     * @brief Interface of the meshed deformable body of a scene.
     *
     * A geometry builds the mesh of the slave body and sets boundary ids that
     * the `Boundary conditions` and `Contact` subsections refer to. Every
     * built-in geometry uses the same convention where it applies:
     * 2 = bottom (the candidate contact surface), 3 = top (loaded face),
     * 0/1 = the faces at x min / x max, 4/5 = the faces at y min / y max (3D).
     */
    template <int dim> class Interface
    {
    public:
      virtual ~Interface() = default;

      /**
       * @brief Build the (refined) mesh and set its boundary ids. The
       * triangulation is distributed (p4est) for hypercube cells and serial
       * for simplex cells (ContactProblem distributes it afterwards).
       */
      virtual void
      create_mesh(Triangulation<dim> &triangulation) const = 0;

      /** @brief Whether the mesh is made of triangles (2D) or tetrahedra (3D). */
      virtual bool
      simplex_cells() const
      {
        return false;
      }

      /**
       * @brief Names of boundaries (a mesh file's physical groups of dimension
       * dim − 1) with their boundary ids; the
       * `Boundary conditions` and `Contact` entries may use them instead of ids.
       */
      virtual std::map<std::string, types::boundary_id>
      boundary_names() const
      {
        return {};
      }

      /**
       * @brief A boundary the geometry makes of the curved faces near a
       * point: the faces whose centre lies within @p radius of @p centre get
       * @p id, the others @p outside_id; @p entry is the radius's entry
       * (`Geometry/half ball/Contact zone radius`).
       */
      struct ContactZone
      {
        types::boundary_id id, outside_id;
        Point<dim>         centre;
        double             radius;
        std::string        entry;
      };

      /**
       * @brief The contact zones of the geometry (none: a block, a mesh
       * file), for the messages about a zone that holds no face.
       */
      virtual std::vector<ContactZone>
      contact_zones() const
      {
        return {};
      }

      /**
       * @brief Names of the bodies (a mesh file's physical groups of dimension
       * dim) with their material ids; the `Material 2`, `Material 3` slots may
       * use them.
       */
      virtual std::map<std::string, types::material_id>
      body_names() const
      {
        return {};
      }

      /** @brief Estimate the run before the mesh's uniform refinement (refine_global()). */
      void
      set_size_check(std::shared_ptr<const SizeCheck> check)
      {
        size_check = std::move(check);
      }

    protected:
      /**
       * @brief Refine @p triangulation uniformly @p refinements times, once the
       * size check has estimated the run on the refined mesh: it refuses
       * what cannot fit before anything is allocated.
       */
      void
      refine_global(Triangulation<dim> &triangulation, const unsigned int refinements) const
      {
        if (size_check)
          {
            // the block and the balls split each refined hypercube into simplices
            // (GridGenerator::convert_hypercube_to_simplex_mesh)
            const bool split =
                simplex_cells() && triangulation.all_reference_cells_are_hyper_cube();
            size_check->before_refinement(triangulation.n_active_cells(),
                                          refinements,
                                          split ? (dim == 2 ? 8 : 24) : 1,
                                          simplex_cells());
          }
        triangulation.refine_global(refinements);
      }

    private:
      std::shared_ptr<const SizeCheck> size_check;
    };

    /** @brief The registry of geometries for dimension @p dim. */
    template <int dim> using Registry = PluginRegistry<Interface<dim>>;

    /** @brief Declare the `Geometry` subsection with every registered geometry. */
    template <int dim>
    void
    declare_parameters(ParameterHandler &prm)
    {
      Registry<dim>::declare_parameters_in(
          prm,
          "Geometry",
          "block",
          "Mesh of the deformable body. Boundary ids of the built-in geometries: block: 0 "
          "and 1 the faces at x min and x max, 2 the bottom (the contact surface), 3 the top, "
          "4 and 5 the faces at y min and y max (3D); half ball: 2 the curved faces within "
          "`Contact zone radius` of the lowest point, 0 the rest of the curved side, 3 the "
          "flat side. gmsh: the file's physical groups, by name or id.");
      prm.enter_subsection("Geometry");
      prm.declare_entry(
          "Axisymmetric",
          "false",
          Patterns::Bool(),
          "2D only. false: plane strain (forces per unit thickness, N/mm). true: the mesh is "
          "the meridian section of a solid of revolution about the y axis, x = r >= 0 the "
          "radius (hoop strain u_r/r, integrals weighted by 2 pi r; forces, reactions and "
          "energies are totals over the circumference, in N). The nodes on the axis r = 0 are "
          "held at u_r = 0 without a Dirichlet condition. Loads and obstacles must be "
          "axisymmetric too; a point load is a ring load of that total force.");
      prm.leave_subsection();
    }

    /** @brief Build the geometry chosen in the `Geometry` subsection. */
    template <int dim>
    std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm)
    {
      return Registry<dim>::create_from(prm, "Geometry");
    }
  } // namespace Geometry
} // namespace StabilizedLagrangian
