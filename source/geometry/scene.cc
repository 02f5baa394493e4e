#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <stabilized_lagrangian/geometry/mesh_building.h>
#include <stabilized_lagrangian/geometry/scene.h>

#include <cmath>
#include <functional>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    using namespace MeshBuilding;

    /**
     * @brief Rectangular block (the patin of seed Fig. 2): x in [−L/2, L/2]
     * (or from `Left side`), height H above the plane y = 0 (2D) or z = 0
     * (3D), width W in y (3D).
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
        prm.declare_entry("Left side",
                          "centred",
                          Patterns::Anything(),
                          "x of the face at x min (mm), or centred: -Length/2. 0 with "
                          "Geometry/Axisymmetric = true makes the block a solid cylinder of "
                          "radius Length about the y axis.");
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

      Block(const ParameterHandler &prm, const std::string &section)
          : length(prm.get_double("Length"))
          , height(prm.get_double("Height"))
          , width(prm.get_double("Width"))
          , refinements(prm.get_integer("Global refinements"))
          , local_refinements(prm.get_integer("Local refinements"))
          , refinement_radius(prm.get_double("Local refinement radius"))
          , simplex(
                read_cell_shape<dim>(prm, section, local_refinements > 0 && refinement_radius > 0.))
      {
        const auto coordinates = Utilities::split_string_list(prm.get("Local refinement center"));
        for (unsigned int d = 0; d < dim; ++d)
          refinement_center[d] = Utilities::string_to_double(coordinates[d]);
        for (const auto &s : Utilities::split_string_list(prm.get("Subdivisions")))
          subdivisions.push_back(Utilities::string_to_int(s));
        if (!(length > 0. && height > 0. && width > 0.))
          throw InputError(section + ": Length, Height and Width must be > 0.");
        const std::string left = prm.get("Left side");
        try
          {
            left_side = left == "centred" ? -length / 2. : Utilities::string_to_double(left);
          }
        catch (...)
          {
            throw InputError(section + "/Left side = '" + left +
                             "': give a number (mm) or centred.");
          }
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
        lower[0]       = left_side;
        upper[0]       = left_side + length;
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
        this->refine_global(triangulation, refinements);
        if (simplex)
          split_into_simplices(triangulation);
        refine_near(triangulation, refinement_center, refinement_radius, local_refinements);
      }

    private:
      const double              length, height, width;
      const unsigned int        refinements, local_refinements;
      const double              refinement_radius;
      const bool                simplex;
      double                    left_side;
      Point<dim>                refinement_center;
      std::vector<unsigned int> subdivisions;
    };

    /**
     * @brief Half disc (2D: a cylinder in plane strain) or half ball (3D) of radius R
     * whose curved side touches the plane y = 0 (z = 0) at the origin, for the Hertz
     * problem. The flat side (id 3) is at height R; the curved faces within
     * `Contact zone radius` of the origin get id 2, the rest id 0. Cells near
     * the origin are refined `Local refinements` times. With `Symmetry planes`
     * only x ≥ 0 (and y ≥ 0 in 3D) is meshed, from deal.II's quarter ball: the
     * planes x = 0 (id 4) and y = 0 (id 5, 3D) are the model's symmetry planes.
     */
    template <int dim> class HalfBall : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_ball_parameters(
            prm, "Distance (mm) from the contact point within which cells are refined.");
        prm.declare_entry("Symmetry planes",
                          "false",
                          Patterns::Bool(),
                          "true: mesh only x >= 0 (and y >= 0 in 3D), a half (2D) or quarter "
                          "(3D) model whose planes x = 0 (id 4) and y = 0 (id 5) are symmetry "
                          "planes: hold their normal displacement with Dirichlet conditions. "
                          "Forces are then those of the half (quarter) body.");
        declare_cell_shape(prm);
      }

      HalfBall(const ParameterHandler &prm, const std::string &section)
          : radius(prm.get_double("Radius"))
          , global_refinements(prm.get_integer("Global refinements"))
          , local_refinements(prm.get_integer("Local refinements"))
          , refinement_radius(prm.get_double("Local refinement radius"))
          , contact_radius(contact_zone_radius(prm, section, radius))
          , zone_entry(section + "/Contact zone radius")
          , symmetric(prm.get_bool("Symmetry planes"))
          , simplex(
                read_cell_shape<dim>(prm, section, local_refinements > 0 && refinement_radius > 0.))
      {
        if (!(radius > 0.))
          throw InputError(section + "/Radius must be > 0.");
      }

      bool
      simplex_cells() const override
      {
        return simplex;
      }

      /** Id 2 about the lowest point, the origin; the rest of the curved side id 0. */
      std::vector<typename Interface<dim>::ContactZone>
      contact_zones() const override
      {
        return {{2, 0, Point<dim>(), contact_radius, zone_entry}};
      }

      void
      create_mesh(Triangulation<dim> &triangulation) const override
      {
        if (symmetric)
          {
            create_symmetric_mesh(triangulation);
            return;
          }
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
        this->refine_global(triangulation, global_refinements);
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
          close_contact_zone(triangulation, 2);
      }

    private:
      /** The half (2D) or quarter (3D) model: ids 4 and 5 on its symmetry planes. */
      void
      create_symmetric_mesh(Triangulation<dim> &triangulation) const
      {
        GridGenerator::quarter_hyper_ball(triangulation, Point<dim>(), radius);
        // the orthant turned below the centre, its lowest point at the origin
        Point<dim> center;
        center[dim - 1] = radius;
        turn_orthant_below(triangulation, center);
        triangulation.set_manifold(0, SphericalManifold<dim>(center));
        this->refine_global(triangulation, global_refinements);
        if (simplex)
          split_into_simplices(triangulation);
        refine_near(triangulation, Point<dim>(), refinement_radius, local_refinements);
        const double tolerance = 1e-8 * radius;
        for (const auto &cell : triangulation.active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                const Point<dim> x = face->center();
                if (std::abs(x[0]) < tolerance)
                  face->set_boundary_id(4);
                else if (dim == 3 && std::abs(x[1]) < tolerance)
                  face->set_boundary_id(5);
                else if (std::abs(x[dim - 1] - radius) < tolerance)
                  face->set_boundary_id(3);
                else if (x.norm() < contact_radius)
                  face->set_boundary_id(2);
                else
                  face->set_boundary_id(0);
              }
        if (dim == 3)
          close_contact_zone(triangulation, 2);
      }

      const double       radius;
      const unsigned int global_refinements, local_refinements;
      const double       refinement_radius, contact_radius;
      const std::string  zone_entry;
      const bool         symmetric;
      const bool         simplex;
    };

    /**
     * @brief Two equal elastic balls (3D) or cylinders (2D, plane strain) of
     * radius R pressed together, as a symmetric model: the quarter of each
     * ball on x ≥ 0, y ≥ 0 (3D), the half of each cylinder on x ≥ 0 (2D). The
     * lower body is the upper half of the ball centred at (0, −R) (0, 0, −R),
     * its pole at the origin; the upper body the lower half of the ball
     * centred `Initial gap` above the pole plus R, its pole at the gap. The
     * bodies share no vertex (a positive gap keeps the poles apart).
     * Boundaries (ids and names): 2 upper_contact and 7 lower_contact (the
     * curved faces within `Contact zone radius` of the poles), 0 the rest of
     * the curved faces, 3 upper_top (the upper body's flat face), 6
     * lower_bottom, 4 symmetry_x (x = 0), 5 symmetry_y (y = 0, 3D). Bodies:
     * material ids 1 upper, 2 lower.
     */
    template <int dim> class TwoBalls : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_ball_parameters(prm,
                                "Distance (mm) from the contact point within which the last "
                                "local refinement refines; each earlier one refines within "
                                "twice the distance of the next (a geometric grading).");
        prm.declare_entry("Initial gap",
                          "0.01",
                          Patterns::Double(),
                          "Distance (mm) between the poles before loading, > 0.");
      }

      TwoBalls(const ParameterHandler &prm, const std::string &section)
          : radius(prm.get_double("Radius"))
          , gap(prm.get_double("Initial gap"))
          , global_refinements(prm.get_integer("Global refinements"))
          , local_refinements(prm.get_integer("Local refinements"))
          , refinement_radius(prm.get_double("Local refinement radius"))
          , contact_radius(contact_zone_radius(prm, section, radius))
          , zone_entry(section + "/Contact zone radius")
      {
        if (!(radius > 0.))
          throw InputError(section + "/Radius must be > 0.");
        if (!(gap > 0. && gap < radius))
          throw InputError(section +
                           "/Initial gap must be > 0 (the poles of the two "
                           "bodies must not share a vertex) and smaller than the radius.");
      }

      void
      create_mesh(Triangulation<dim> &triangulation) const override
      {
        // each body: the quarter (3D: eighth) of a ball, curved manifold 0
        Point<dim> lower_center, upper_center;
        lower_center[dim - 1] = -radius;
        upper_center[dim - 1] = radius + gap;
        Triangulation<dim> lower, upper, both;
        GridGenerator::quarter_hyper_ball(lower, lower_center, radius);
        GridGenerator::quarter_hyper_ball(upper, Point<dim>(), radius);
        // the upper body's orthant turned below its centre
        turn_orthant_below(upper, upper_center);
        for (const auto &cell : upper.active_cell_iterators())
          {
            cell->set_material_id(1);
            for (const auto &face : cell->face_iterators())
              if (face->manifold_id() == 0)
                face->set_all_manifold_ids(1);
          }
        for (const auto &cell : lower.active_cell_iterators())
          cell->set_material_id(2);
        GridGenerator::merge_triangulations(upper, lower, both, 1e-12 * radius, true);
        triangulation.copy_triangulation(both);
        triangulation.set_manifold(0, SphericalManifold<dim>(lower_center));
        triangulation.set_manifold(1, SphericalManifold<dim>(upper_center));
        this->refine_global(triangulation, global_refinements);
        Point<dim> contact_point;
        contact_point[dim - 1] = gap / 2.;
        for (unsigned int step = 0; step < local_refinements; ++step)
          refine_near(triangulation,
                      contact_point,
                      refinement_radius * std::pow(2., local_refinements - 1 - step),
                      1);

        const double tolerance = 1e-8 * radius;
        for (const auto &cell : triangulation.active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                const Point<dim> x          = face->center();
                const bool       upper_body = cell->material_id() == 1;
                Point<dim>       pole;
                pole[dim - 1] = upper_body ? gap : 0.;
                if (std::abs(x[0]) < tolerance)
                  face->set_boundary_id(4);
                else if (dim == 3 && std::abs(x[1]) < tolerance)
                  face->set_boundary_id(5);
                else if (std::abs(x[dim - 1] - upper_center[dim - 1]) < tolerance)
                  face->set_boundary_id(3);
                else if (std::abs(x[dim - 1] - lower_center[dim - 1]) < tolerance)
                  face->set_boundary_id(6);
                else if (x.distance(pole) < contact_radius)
                  face->set_boundary_id(upper_body ? 2 : 7);
                else
                  face->set_boundary_id(0);
              }
        if (dim == 3)
          {
            close_contact_zone(triangulation, 2);
            close_contact_zone(triangulation, 7);
          }
      }

      std::map<std::string, types::boundary_id>
      boundary_names() const override
      {
        std::map<std::string, types::boundary_id> names = {{"upper_contact", 2},
                                                           {"lower_contact", 7},
                                                           {"upper_top", 3},
                                                           {"lower_bottom", 6},
                                                           {"symmetry_x", 4}};
        if (dim == 3)
          names["symmetry_y"] = 5;
        return names;
      }

      std::map<std::string, types::material_id>
      body_names() const override
      {
        return {{"upper", 1}, {"lower", 2}};
      }

      /** Id 2 about the upper pole, id 7 about the lower one; the rest of the curved faces id 0. */
      std::vector<typename Interface<dim>::ContactZone>
      contact_zones() const override
      {
        Point<dim> upper_pole;
        upper_pole[dim - 1] = gap;
        return {{2, 0, upper_pole, contact_radius, zone_entry},
                {7, 0, Point<dim>(), contact_radius, zone_entry}};
      }

    private:
      const double       radius, gap;
      const unsigned int global_refinements, local_refinements;
      const double       refinement_radius, contact_radius;
      const std::string  zone_entry;
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
    SL_REGISTER_PLUGIN(Interface,
                       TwoBalls,
                       "two balls",
                       "two equal balls (3D, quarter model) or cylinders (2D, half model) "
                       "pressed together: Hertz between two deformable bodies");

  } // namespace Geometry
} // namespace StabilizedLagrangian
