#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <stabilized_lagrangian/geometry/scene.h>

#include <functional>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    namespace
    {
      /** Refine @p steps times the cells whose centre lies within @p radius of @p center. */
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

      /** Whether `Cell shape` asks for simplices; refuse what they cannot do. */
      template <int dim>
      bool
      read_cell_shape(const ParameterHandler &prm,
                      const std::string      &geometry,
                      const bool              local_refinement)
      {
        const bool simplex = prm.get("Cell shape") == "simplex";
        if (simplex && dim == 3 && local_refinement)
          throw InputError("Geometry/" + geometry +
                           "/Local refinements must be 0 with Cell shape = simplex in 3D: "
                           "deal.II 9.4 cannot constrain the hanging nodes of tetrahedra. "
                           "Refine uniformly (Global refinements) instead.");
        return simplex;
      }

      /**
       * Replace the uniformly refined hypercube mesh @p triangulation (serial)
       * by its split into simplices, keeping boundary and material ids.
       */
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
    } // namespace

    /**
     * @brief Rectangular block (the patin of seed Fig. 2): x in [−L/2, L/2],
     * height H above the plane y = 0 (2D) or z = 0 (3D), width W in y (3D).
     */
    template <int dim> class Block : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Length", "100", Patterns::Double(), "Extent in x (mm), > 0.");
        prm.declare_entry(
            "Height", "50", Patterns::Double(), "Extent in the vertical direction (mm), > 0.");
        prm.declare_entry("Width", "50", Patterns::Double(), "Extent in y, 3D only (mm), > 0.");
        prm.declare_entry("Subdivisions",
                          dim == 2 ? "2, 1" : "2, 1, 1",
                          Patterns::List(Patterns::Integer(1), dim, dim),
                          "Cells of the coarse mesh along x, (y,) vertical.");
        prm.declare_entry(
            "Global refinements", "3", Patterns::Integer(0, 12), "Uniform refinements.");
        prm.declare_entry("Local refinements",
                          "0",
                          Patterns::Integer(0, 12),
                          "Refinements of the cells within `Local refinement radius` of "
                          "`Local refinement center`, after the uniform ones (hanging nodes).");
        prm.declare_entry("Local refinement center",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Centre of the locally refined region (mm).");
        prm.declare_entry("Local refinement radius",
                          "0",
                          Patterns::Double(0.),
                          "Radius of the locally refined region (mm).");
        declare_cell_shape(prm);
      }

      explicit Block(const ParameterHandler &prm)
          : length(prm.get_double("Length"))
          , height(prm.get_double("Height"))
          , width(prm.get_double("Width"))
          , refinements(prm.get_integer("Global refinements"))
          , local_refinements(prm.get_integer("Local refinements"))
          , refinement_radius(prm.get_double("Local refinement radius"))
          , simplex(
                read_cell_shape<dim>(prm, "block", local_refinements > 0 && refinement_radius > 0.))
      {
        const auto coordinates = Utilities::split_string_list(prm.get("Local refinement center"));
        for (unsigned int d = 0; d < dim; ++d)
          refinement_center[d] = Utilities::string_to_double(coordinates[d]);
        for (const auto &s : Utilities::split_string_list(prm.get("Subdivisions")))
          subdivisions.push_back(Utilities::string_to_int(s));
        if (!(length > 0. && height > 0. && width > 0.))
          throw InputError("Geometry/block: Length, Height and Width must be > 0.");
      }

      bool
      simplex_cells() const override
      {
        return simplex;
      }

      void
      create_mesh(Triangulation<dim> &triangulation) const override
      {
        Point<dim> lower, upper;
        lower[0]       = -length / 2.;
        upper[0]       = length / 2.;
        upper[dim - 1] = height;
        if (dim == 3)
          {
            lower[1] = -width / 2.;
            upper[1] = width / 2.;
          }
        GridGenerator::subdivided_hyper_rectangle(triangulation, subdivisions, lower, upper, true);
        if (dim == 3)
          {
            // colorize numbers y faces 2/3 and z faces 4/5; the convention wants
            // the vertical faces to be 2 (bottom) and 3 (top)
            const std::map<types::boundary_id, types::boundary_id> renumber = {
                {2, 4}, {3, 5}, {4, 2}, {5, 3}};
            for (const auto &cell : triangulation.active_cell_iterators())
              for (const auto &face : cell->face_iterators())
                if (face->at_boundary() && renumber.count(face->boundary_id()))
                  face->set_boundary_id(renumber.at(face->boundary_id()));
          }
        triangulation.refine_global(refinements);
        if (simplex)
          split_into_simplices(triangulation);
        refine_near(triangulation, refinement_center, refinement_radius, local_refinements);
      }

    private:
      const double              length, height, width;
      const unsigned int        refinements, local_refinements;
      const double              refinement_radius;
      const bool                simplex;
      Point<dim>                refinement_center;
      std::vector<unsigned int> subdivisions;
    };

    /**
     * @brief Half disc (2D: a cylinder in plane strain) or half ball (3D) of radius R
     * whose curved side touches the plane y = 0 (z = 0) at the origin, for the Hertz
     * problem. The flat side (id 3) is at height R; the curved faces within
     * `Contact zone radius` of the origin get id 2, the rest id 0. Cells near
     * the origin are refined `Local refinements` times.
     */
    template <int dim> class HalfBall : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Radius", "100", Patterns::Double(), "Radius R (mm), > 0.");
        prm.declare_entry(
            "Global refinements", "3", Patterns::Integer(0, 12), "Uniform refinements.");
        prm.declare_entry("Local refinements",
                          "3",
                          Patterns::Integer(0, 12),
                          "Refinements of the cells within `Local refinement radius` of the "
                          "lowest point, after the uniform ones.");
        prm.declare_entry("Local refinement radius",
                          "30",
                          Patterns::Double(),
                          "Distance (mm) from the lowest point within which cells are refined.");
        prm.declare_entry("Contact zone radius",
                          "20",
                          Patterns::Double(),
                          "Curved faces within this distance (mm) of the lowest point form "
                          "the candidate contact surface (id 2). When it is larger than the "
                          "local refinement radius, the contact mesh has hanging nodes.");
        declare_cell_shape(prm);
      }

      explicit HalfBall(const ParameterHandler &prm)
          : radius(prm.get_double("Radius"))
          , global_refinements(prm.get_integer("Global refinements"))
          , local_refinements(prm.get_integer("Local refinements"))
          , refinement_radius(prm.get_double("Local refinement radius"))
          , contact_radius(prm.get_double("Contact zone radius"))
          , simplex(read_cell_shape<dim>(
                prm, "half ball", local_refinements > 0 && refinement_radius > 0.))
      {
        if (!(radius > 0.))
          throw InputError("Geometry/half ball/Radius must be > 0.");
      }

      bool
      simplex_cells() const override
      {
        return simplex;
      }

      void
      create_mesh(Triangulation<dim> &triangulation) const override
      {
        GridGenerator::half_hyper_ball(triangulation, Point<dim>(), radius);
        double min_x = 0.;
        for (const auto &v : triangulation.get_vertices())
          min_x = std::min(min_x, v[0]);
        const bool kept_positive_x = (min_x > -1e-10 * radius);
        // an orientation-preserving rotation taking the kept half below the centre,
        // then a shift putting the lowest point at the origin
        GridTools::transform(
            [&](const Point<dim> &p) {
              Point<dim> q = p;
              q[0]         = kept_positive_x ? p[dim - 1] : -p[dim - 1];
              q[dim - 1]   = kept_positive_x ? -p[0] : p[0];
              q[dim - 1] += radius;
              return q;
            },
            triangulation);
        Point<dim> center;
        center[dim - 1] = radius;
        triangulation.set_manifold(0, SphericalManifold<dim>(center));
        triangulation.refine_global(global_refinements);
        if (simplex)
          split_into_simplices(triangulation);
        refine_near(triangulation, Point<dim>(), refinement_radius, local_refinements);
        for (const auto &cell : triangulation.active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                if (face->boundary_id() == 1)
                  face->set_boundary_id(3);
                else if (face->center().norm() < contact_radius)
                  face->set_boundary_id(2);
                else
                  face->set_boundary_id(0);
              }
        if (dim == 3)
          close_contact_zone(triangulation);
      }

    private:
      /**
       * In 3D, the children of a refined face all join the contact zone when
       * one of them is in it: where the zone ended inside a refined face, a
       * hanging vertex of Γc would be constrained to a vertex off Γc, which
       * has no multiplier. (In 2D the boundary has no hanging vertices.)
       */
      static void
      close_contact_zone(Triangulation<dim> &triangulation)
      {
        const std::function<void(const typename Triangulation<dim>::face_iterator &)> join =
            [&join](const typename Triangulation<dim>::face_iterator &face) {
              face->set_boundary_id(2);
              if (face->has_children())
                for (unsigned int c = 0; c < face->n_children(); ++c)
                  join(face->child(c));
            };
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->level() > 0)
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 2)
                join(cell->parent()->face(f));
      }

    private:
      const double       radius;
      const unsigned int global_refinements, local_refinements;
      const double       refinement_radius, contact_radius;
      const bool         simplex;
    };

    SL_REGISTER_PLUGIN(Interface,
                       Block,
                       "block",
                       "rectangular block resting on y = 0 (z = 0 in 3D)");
    SL_REGISTER_PLUGIN(Interface,
                       HalfBall,
                       "half ball",
                       "half disc / half ball touching y = 0 (z = 0) at the origin "
                       "(Hertz problem)");

  } // namespace Geometry
} // namespace StabilizedLagrangian
