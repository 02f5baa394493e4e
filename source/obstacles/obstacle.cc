#include <deal.II/base/patterns.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria_description.h>

#include <stabilized_lagrangian/obstacles/obstacle.h>

#include <sstream>

namespace StabilizedLagrangian
{
  namespace Obstacles
  {
    namespace
    {
      Tensor<1, 3>
      parse_vector(const std::string &entry, const std::string &text, const unsigned int dim)
      {
        const std::vector<double> values =
            Utilities::string_to_double(Utilities::split_string_list(text));
        if (values.size() != dim)
          throw InputError(entry + " needs " + std::to_string(dim) +
                           " comma-separated numbers, got '" + text + "'.");
        Tensor<1, 3> v;
        for (unsigned int d = 0; d < dim; ++d)
          v[d] = values[d];
        return v;
      }

      template <int dim>
      Point<dim>
      to_point(const Tensor<1, 3> &v)
      {
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = v[d];
        return p;
      }
    } // namespace

    /**
     * @brief Rigid half-space below a plane through a point with outward unit normal.
     */
    template <int dim> class Plane : public Interface<dim>
    {
    public:
      /** @param section the obstacle's subsection, for messages */
      Plane(const Point<dim> &point, const Tensor<1, dim> &normal, const std::string &section)
          : point(point)
          , normal(normal / normal.norm())
          , tangents(tangent_basis(this->normal))
          , section(section)
      {
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Point",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Patterns::List(Patterns::Double(), dim, dim),
                          "A point of the plane (mm).");
        prm.declare_entry("Normal",
                          dim == 2 ? "0, 1" : "0, 0, 1",
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Normal of the plane pointing out of the obstacle, towards the body.");
      }

      /** @brief The plane of the `Point` and `Normal` entries of @p section. */
      Plane(const ParameterHandler &prm, const std::string &section)
          : Plane(to_point<dim>(parse_vector(section + "/Point", prm.get("Point"), dim)),
                  nonzero_normal(prm, section),
                  section)
      {
      }

      Pairing<dim>
      project(const Point<dim> &x) const override
      {
        Pairing<dim> pairing;
        pairing.normal       = normal;
        pairing.tangents     = tangents;
        pairing.master_point = x - ((x - point) * normal) * normal;
        return pairing;
      }

      bool
      is_flat() const override
      {
        return true;
      }

      /** A plane normal to the axis; a tilted one revolves into a cone. */
      std::string
      axisymmetry_defect(const Tensor<1, dim> &axis) const override
      {
        if ((normal - (normal * axis) * axis).norm() <= 1e-10)
          return "";
        std::ostringstream why;
        why << section << "/Normal points along (" << normal << "), not along the axis (" << axis
            << "): the tilted plane's profile revolves into a cone, not a plane";
        return why.str();
      }

      /** The body's box projected on the plane, enlarged by a fifth: a segment or a rectangle. */
      void
      make_surface_mesh(Triangulation<dim - 1, dim> &surface,
                        const BoundingBox<dim>      &body) const override
      {
        const Point<dim> centre = project(body.center()).master_point;
        double           size   = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          size = std::max(size, body.side_length(d));
        const double            half = 0.6 * size;
        std::vector<Point<dim>> vertices;
        for (unsigned int v = 0; v < (1u << (dim - 1)); ++v)
          {
            Point<dim> vertex = centre;
            for (unsigned int a = 0; a < dim - 1; ++a)
              vertex += ((v >> a) & 1 ? half : -half) * tangents[a];
            vertices.push_back(vertex);
          }
        std::vector<CellData<dim - 1>> cells(1);
        for (unsigned int v = 0; v < vertices.size(); ++v)
          cells[0].vertices[v] = v;
        surface.create_triangulation(vertices, cells, SubCellData());
      }

    private:
      static Tensor<1, dim>
      nonzero_normal(const ParameterHandler &prm, const std::string &section)
      {
        const Point<dim> normal =
            to_point<dim>(parse_vector(section + "/Normal", prm.get("Normal"), dim));
        if (normal.norm() == 0.)
          throw InputError(section + "/Normal must not be the zero vector.");
        return Tensor<1, dim>(normal);
      }

      const Point<dim>                          point;
      const Tensor<1, dim>                      normal;
      const std::array<Tensor<1, dim>, dim - 1> tangents;
      const std::string                         section;
    };

    /**
     * @brief Rigid disc (2D, a cylinder in plane strain) or ball (3D); the body is outside.
     */
    template <int dim> class Ball : public Interface<dim>
    {
    public:
      /** @param section the obstacle's subsection, for messages */
      Ball(const Point<dim> &center, const double radius, const std::string &section)
          : center(center)
          , radius(radius)
          , section(section)
      {
        if (!(radius > 0.))
          throw InputError(section + "/Radius must be > 0.");
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Center",
                          dim == 2 ? "0, -100" : "0, 0, -100",
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Centre of the rigid disc (2D) or ball (3D), mm.");
        prm.declare_entry("Radius", "100", Patterns::Double(), "Radius (mm), > 0.");
      }

      /** @brief The ball of the `Center` and `Radius` entries of @p section. */
      Ball(const ParameterHandler &prm, const std::string &section)
          : Ball(to_point<dim>(parse_vector(section + "/Center", prm.get("Center"), dim)),
                 prm.get_double("Radius"),
                 section)
      {
      }

      Pairing<dim>
      project(const Point<dim> &x) const override
      {
        Pairing<dim>         pairing;
        const Tensor<1, dim> d        = x - center;
        const double         distance = d.norm();
        if (distance > 0.)
          pairing.normal = d / distance;
        else
          pairing.normal[dim - 1] = 1.;
        pairing.master_point = center + radius * pairing.normal;
        pairing.tangents     = tangent_basis(pairing.normal);
        if (distance > 0.)
          {
            // n = (x − c)/|x − c|: ∂n/∂x = (I − n⊗n)/|x − c|
            const Tensor<2, dim> identity = unit_symmetric_tensor<dim>();
            pairing.normal_gradient =
                (identity - outer_product(pairing.normal, pairing.normal)) / distance;
            const auto dt_dn = tangent_basis_derivative(pairing.normal);
            for (unsigned int a = 0; a < dim - 1; ++a)
              pairing.tangent_gradients[a] = dt_dn[a] * pairing.normal_gradient;
          }
        return pairing;
      }

      bool
      is_flat() const override
      {
        return false;
      }

      /** A ball centred on the axis; one off it revolves into a torus. */
      std::string
      axisymmetry_defect(const Tensor<1, dim> &axis) const override
      {
        const double off_axis = (center - (center * axis) * axis).norm();
        if (off_axis <= 1e-10 * radius)
          return "";
        std::ostringstream why;
        why << section << "/Center = " << center << " lies " << off_axis << " mm off the axis ("
            << axis << "): the disc's profile revolves into a torus, not a ball";
        return why.str();
      }

      /** The whole circle (2D) or sphere (3D), refined until its facets look round. */
      void
      make_surface_mesh(Triangulation<dim - 1, dim> &surface,
                        const BoundingBox<dim> &) const override
      {
        GridGenerator::hyper_sphere(surface, center, radius);
        surface.refine_global(dim == 2 ? 5 : 4);
      }

    private:
      const Point<dim>  center;
      const double      radius;
      const std::string section;
    };

    SL_REGISTER_PLUGIN(Interface, Plane, "plane", "rigid half-space bounded by a plane");
    SL_REGISTER_PLUGIN(Interface,
                       Ball,
                       "ball",
                       "rigid disc (2D cylinder) or sphere (3D); the body is outside");

  } // namespace Obstacles
} // namespace StabilizedLagrangian
