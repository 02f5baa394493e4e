#include <deal.II/base/patterns.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/obstacles/obstacle.h>

namespace StabilizedLagrangian
{
  namespace Obstacles
  {
    namespace
    {
      /** The coordinate axis least aligned with @p n: it gives a well-conditioned t_0. */
      template <int dim>
      Tensor<1, dim>
      least_aligned_axis(const Tensor<1, dim> &n)
      {
        unsigned int axis = 0;
        for (unsigned int d = 1; d < dim; ++d)
          if (std::abs(n[d]) < std::abs(n[axis]))
            axis = d;
        Tensor<1, dim> e;
        e[axis] = 1.;
        return e;
      }
    } // namespace

    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n)
    {
      std::array<Tensor<1, dim>, dim - 1> t;
      if constexpr (dim == 2)
        {
          t[0][0] = n[1];
          t[0][1] = -n[0];
        }
      else
        {
          const Tensor<1, dim> e = least_aligned_axis(n);
          t[0]                   = e - (e * n) * n;
          t[0] /= t[0].norm();
          t[1] = cross_product_3d(n, t[0]);
        }
      return t;
    }

    template <int dim>
    std::array<Tensor<2, dim>, dim - 1>
    tangent_basis_derivative(const Tensor<1, dim> &n)
    {
      std::array<Tensor<2, dim>, dim - 1> d;
      if constexpr (dim == 2)
        {
          // t = (n_1, −n_0)
          d[0][0][1] = 1.;
          d[0][1][0] = -1.;
        }
      else
        {
          // t_0 = a/|a| with a = e − (e·n) n, t_1 = n × t_0; e is the fixed axis
          // of tangent_basis(), so the derivative holds away from the switches
          const Tensor<1, dim> e      = least_aligned_axis(n);
          const Tensor<1, dim> a      = e - (e * n) * n;
          const double         a_norm = a.norm();
          const Tensor<1, dim> t0     = a / a_norm;
          // ∂a_i/∂n_j = −n_i e_j − (e·n) δ_ij
          const Tensor<2, dim> identity = unit_symmetric_tensor<dim>();
          const Tensor<2, dim> da       = -outer_product(n, e) - (e * n) * identity;
          d[0]                          = (identity - outer_product(t0, t0)) * da / a_norm;
          // ∂(n × t_0)_i/∂n_j = ε_ijl t0_l + ε_ikl n_k ∂t0_l/∂n_j
          for (unsigned int j = 0; j < dim; ++j)
            {
              Tensor<1, dim> ej, dt0;
              ej[j] = 1.;
              for (unsigned int l = 0; l < dim; ++l)
                dt0[l] = d[0][l][j];
              const Tensor<1, dim> column = cross_product_3d(ej, t0) + cross_product_3d(n, dt0);
              for (unsigned int i = 0; i < dim; ++i)
                d[1][i][j] = column[i];
            }
        }
      return d;
    }

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
      Plane(const Point<dim> &point, const Tensor<1, dim> &normal)
          : point(point)
          , normal(normal / normal.norm())
          , tangents(tangent_basis(this->normal))
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

      /** @brief The plane of the `Point` and `Normal` entries. */
      explicit Plane(const ParameterHandler &prm)
          : Plane(to_point<dim>(parse_vector("Obstacle/plane/Point", prm.get("Point"), dim)),
                  nonzero_normal(prm))
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

    private:
      static Tensor<1, dim>
      nonzero_normal(const ParameterHandler &prm)
      {
        const Point<dim> normal =
            to_point<dim>(parse_vector("Obstacle/plane/Normal", prm.get("Normal"), dim));
        if (normal.norm() == 0.)
          throw InputError("Obstacle/plane/Normal must not be the zero vector.");
        return Tensor<1, dim>(normal);
      }

      const Point<dim>                          point;
      const Tensor<1, dim>                      normal;
      const std::array<Tensor<1, dim>, dim - 1> tangents;
    };

    /**
     * @brief Rigid disc (2D, a cylinder in plane strain) or ball (3D); the body is outside.
     */
    template <int dim> class Ball : public Interface<dim>
    {
    public:
      Ball(const Point<dim> &center, const double radius)
          : center(center)
          , radius(radius)
      {
        if (!(radius > 0.))
          throw InputError("Obstacle/ball/Radius must be > 0.");
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

      /** @brief The ball of the `Center` and `Radius` entries. */
      explicit Ball(const ParameterHandler &prm)
          : Ball(to_point<dim>(parse_vector("Obstacle/ball/Center", prm.get("Center"), dim)),
                 prm.get_double("Radius"))
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

    private:
      const Point<dim> center;
      const double     radius;
    };

    SL_REGISTER_PLUGIN(Interface, Plane, "plane", "rigid half-space bounded by a plane");
    SL_REGISTER_PLUGIN(Interface,
                       Ball,
                       "ball",
                       "rigid disc (2D cylinder) or sphere (3D); the body is outside");

    template std::array<Tensor<1, 2>, 1>
    tangent_basis<2>(const Tensor<1, 2> &);
    template std::array<Tensor<1, 3>, 2>
    tangent_basis<3>(const Tensor<1, 3> &);
    template std::array<Tensor<2, 2>, 1>
    tangent_basis_derivative<2>(const Tensor<1, 2> &);
    template std::array<Tensor<2, 3>, 2>
    tangent_basis_derivative<3>(const Tensor<1, 3> &);
  } // namespace Obstacles
} // namespace StabilizedLagrangian
