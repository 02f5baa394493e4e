#pragma once

#include <deal.II/base/array_view.h>
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/pairing.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>

#include <memory>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief The contact partner of the slave boundary: a rigid analytic
     * obstacle (RigidObstacle) or the meshed surface of a second deformable
     * body (MasterSurface). Both pair a slave point with the closest point of
     * their surface, its normal and tangents (doc/formulation.md, "Signs and
     * notation"); a meshed partner also has displacement DoFs, which the
     * pairing couples to the slave's, and a configuration that follows them.
     * The solver holds one partner and asks it, never which one it is.
     */
    template <int dim> class Partner
    {
    public:
      virtual ~Partner() = default;

      /** @brief Closest point, normal and tangents of the current surface for a slave position @p
       * x. */
      virtual Pairing<dim>
      project(const Point<dim> &x) const = 0;

      /**
       * @brief True when the pairing of a frozen normal is exact for every
       * position (a plane), so the geometry loop needs only one iteration.
       */
      virtual bool
      is_flat() const = 0;

      /**
       * @brief True when the surface is rigid and outside the mesh: the whole
       * mesh is the slave body (the scene checks before the run ask it).
       */
      virtual bool
      is_rigid() const = 0;

      /**
       * @brief True when project() gives the pairing's derivatives with respect
       * to the slave position (Pairing::normal_gradient, tangent_gradients), so
       * the generalized Newton linearises the pairing at each point; otherwise
       * it pairs anew before each assembly.
       */
      virtual bool
      has_pairing_derivatives() const = 0;

      /**
       * @brief Deform the surface by the displacement in @p u (ghosts must
       * include dofs()).
       */
      virtual void
      update_configuration(const TrilinosWrappers::MPI::Vector &u) = 0;
      /**
       * @brief The load step from @p start to @p now: a moving partner takes
       * its position at @p now, and follow() measures its motion from @p start.
       */
      virtual void
      set_time(const double start, const double now)
      {
        (void)start;
        (void)now;
      }

      /**
       * @brief Move the frozen pairing's master point x²(ξ) with the partner's
       * displacement in @p u, and return the partner's displacement increment
       * at it since @p step_start, Δu²(ξ), which the slip increment is relative to.
       */
      virtual Tensor<1, dim>
      follow(Pairing<dim>                        &pairing,
             const TrilinosWrappers::MPI::Vector &u,
             const TrilinosWrappers::MPI::Vector &step_start) const = 0;

      /** @brief The partner's displacement DoFs (in the DoFHandler's numbering). */
      virtual const IndexSet &
      dofs() const = 0;

      /** @brief The displacement DoFs of the partner's face @p face (node-major, dim per node). */
      virtual ArrayView<const types::global_dof_index>
      face_dof_indices(const unsigned int face) const = 0;

      /** @brief The displacement DoFs that move the master point of @p pairing. */
      virtual ArrayView<const types::global_dof_index>
      pairing_dof_indices(const Pairing<dim> &pairing) const = 0;

      /**
       * @brief The partner's faces a pairing may move to within a Newton step
       * (those sharing a node with the paired face, itself included).
       */
      virtual const std::vector<unsigned int> &
      faces_near(const Pairing<dim> &pairing) const = 0;

      /**
       * @brief The displacement DoFs of the pairing's master point and their
       * shape values: DoF dofs[i] moves the point by values[i] e_{components[i]}.
       */
      virtual void
      shape_values(const Pairing<dim>                   &pairing,
                   std::vector<types::global_dof_index> &dofs,
                   std::vector<unsigned int>            &components,
                   std::vector<double>                  &values) const = 0;

      /**
       * @brief ∂N_r/∂ξ of the shape values of shape_values(), in its order
       * (nothing for a rigid obstacle, whose pairing moves no DoF).
       */
      virtual void
      shape_gradients(const Pairing<dim> &, std::vector<Tensor<1, dim - 1>> &gradients) const
      {
        gradients.clear();
      }

      /**
       * @brief Vertices of the surface within @p box, where it kinks: the
       * slave faces are integrated in segments between them.
       */
      virtual std::vector<Point<dim>>
      vertices_near(const BoundingBox<dim> &box) const = 0;
    };

    /**
     * @brief A rigid analytic obstacle (an `Obstacle` plug-in) as the contact
     * partner: smooth, without DoFs, fixed in space or translated by a given
     * motion d(t) (`Obstacle/Motion`).
     */
    template <int dim> class RigidObstacle : public Partner<dim>
    {
    public:
      /**
       * @p motion: the translation d(t) (dim components; evaluated at the
       * origin), or null for a fixed obstacle.
       */
      explicit RigidObstacle(const Obstacles::Interface<dim> &obstacle,
                             std::shared_ptr<Function<dim>>   motion = nullptr)
          : obstacle(obstacle)
          , motion(std::move(motion))
      {
      }

      /** The obstacle translated by d: the pairing of x − d, moved by d. */
      Pairing<dim>
      project(const Point<dim> &x) const override
      {
        Pairing<dim> pairing = obstacle.project(x - offset_now);
        pairing.master_point += offset_now;
        pairing.partner_offset = offset_now;
        return pairing;
      }

      void
      set_time(const double start, const double now) override
      {
        offset_start = translation(start);
        offset_now   = translation(now);
      }

      bool
      is_flat() const override
      {
        return obstacle.is_flat();
      }

      bool
      is_rigid() const override
      {
        return true;
      }

      bool
      has_pairing_derivatives() const override
      {
        return true;
      }

      void
      update_configuration(const TrilinosWrappers::MPI::Vector &) override
      {
      }

      /**
       * The frozen pairing's master point moved with the obstacle; the slip is
       * relative to the obstacle's translation since the step's start.
       */
      Tensor<1, dim>
      follow(Pairing<dim> &pairing,
             const TrilinosWrappers::MPI::Vector &,
             const TrilinosWrappers::MPI::Vector &) const override
      {
        pairing.master_point += offset_now - pairing.partner_offset;
        pairing.partner_offset = offset_now;
        return offset_now - offset_start;
      }

      const IndexSet &
      dofs() const override
      {
        return no_dofs;
      }

      ArrayView<const types::global_dof_index>
      face_dof_indices(const unsigned int) const override
      {
        return {};
      }

      ArrayView<const types::global_dof_index>
      pairing_dof_indices(const Pairing<dim> &) const override
      {
        return {};
      }

      const std::vector<unsigned int> &
      faces_near(const Pairing<dim> &) const override
      {
        return no_faces;
      }

      void
      shape_values(const Pairing<dim> &,
                   std::vector<types::global_dof_index> &dofs,
                   std::vector<unsigned int>            &components,
                   std::vector<double>                  &values) const override
      {
        dofs.clear();
        components.clear();
        values.clear();
      }

      std::vector<Point<dim>>
      vertices_near(const BoundingBox<dim> &) const override
      {
        return {};
      }

    private:
      Tensor<1, dim>
      translation(const double t) const
      {
        Tensor<1, dim> d;
        if (motion)
          {
            motion->set_time(t);
            for (unsigned int c = 0; c < dim; ++c)
              d[c] = motion->value(Point<dim>(), c);
          }
        return d;
      }

      const Obstacles::Interface<dim> &obstacle;
      std::shared_ptr<Function<dim>>   motion;
      Tensor<1, dim>                   offset_start, offset_now;
      const IndexSet                   no_dofs;
      const std::vector<unsigned int>  no_faces;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
