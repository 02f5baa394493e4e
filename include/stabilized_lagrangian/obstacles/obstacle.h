#pragma once

#include <deal.II/base/bounding_box.h>

#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/contact/pairing.h>
#include <stabilized_lagrangian/plugins.h>

#include <string>

namespace StabilizedLagrangian
{
  namespace Obstacles
  {
    using namespace dealii;

    using Contact::Pairing;
    using Contact::tangent_basis;
    using Contact::tangent_basis_derivative;

    /**
     * @brief Interface of rigid analytic obstacles (the master surface).
     */
    template <int dim> class Interface
    {
    public:
      virtual ~Interface() = default;

      /** @brief Closest point, normal and tangents for a slave position @p x. */
      virtual Pairing<dim>
      project(const Point<dim> &x) const = 0;

      /**
       * @brief True when the pairing of a frozen normal is exact for every
       * position (a plane), so the geometry loop needs only one iteration.
       */
      virtual bool
      is_flat() const = 0;

      /**
       * @brief Empty when the obstacle is a body of revolution about the line
       * through the origin along the unit vector @p axis (the axis x = 0 of
       * an axisymmetric model, Geometry/Axisymmetric); otherwise why it is
       * not, naming its entries at fault (a tilted plane's `Normal`, the
       * `Center` of a ball off the axis).
       */
      virtual std::string
      axisymmetry_defect(const Tensor<1, dim> &axis) const = 0;

      /**
       * @brief A mesh of the obstacle's surface for the output, at rest: the
       * whole surface where it is bounded (a ball), else the part facing the
       * body's bounding box @p body, enlarged by a fifth (a plane).
       */
      virtual void
      make_surface_mesh(Triangulation<dim - 1, dim> &surface,
                        const BoundingBox<dim>      &body) const = 0;
    };

    /** @brief The registry of obstacles for dimension @p dim. */
    template <int dim> using Registry = PluginRegistry<Interface<dim>>;

    /** @brief Declare the `Obstacle` subsection with every registered obstacle. */
    template <int dim>
    void
    declare_parameters(ParameterHandler &prm)
    {
      Registry<dim>::declare_parameters_in(
          prm, "Obstacle", "plane", "Rigid analytic obstacle (the master).");
    }

    /** @brief Build the obstacle chosen in the `Obstacle` subsection. */
    template <int dim>
    std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm)
    {
      return Registry<dim>::create_from(prm, "Obstacle");
    }
  } // namespace Obstacles
} // namespace StabilizedLagrangian
