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
       * @brief Collective: make sure this rank holds the partner's faces that
       * come within the search distance of @p region (the boxes around this
       * rank's deformed slave faces), in the configuration of @p u (null: the
       * reference configuration; u's ghosts must include this rank's own
       * faces' DoFs). True on every rank when some rank took new faces, so
       * that dofs() grew and the ghosts of the vectors must follow.
       */
      virtual bool
      gather_faces_near(const std::vector<BoundingBox<dim>> &region,
                        const TrilinosWrappers::MPI::Vector *u)
      {
        (void)region;
        (void)u;
        return false;
      }
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
       * since @p step_start, Δu², which the slip increment is relative to: at
       * ξ for a deformable partner, at the slave point's position at the
       * step's start @p slave_start for a rigid one (where the obstacle's
       * rigid motion takes that point).
       */
      virtual Tensor<1, dim>
      follow(Pairing<dim>                        &pairing,
             const TrilinosWrappers::MPI::Vector &u,
             const TrilinosWrappers::MPI::Vector &step_start,
             const Point<dim>                    &slave_start) const = 0;

      /** @brief The partner's displacement DoFs (in the DoFHandler's numbering). */
      virtual const IndexSet &
      dofs() const = 0;

      /** @brief Number of the partner's faces (on all ranks; 0: it has none). */
      virtual unsigned int
      n_faces() const
      {
        return 0;
      }

      /** @brief Number of the partner's faces this rank holds (Contact::MasterSurface). */
      virtual unsigned int
      n_held_faces() const
      {
        return 0;
      }

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

      /** @brief The number of vertices of each face in vertices_near() (0: it has none). */
      virtual unsigned int
      vertices_per_face() const
      {
        return 0;
      }
    };

    /**
     * @brief The rigid motion of an obstacle over time (`Obstacle/Motion`):
     * the translation d(t) and the rotation θ(t) about the centre c, which
     * moves with d (doc/formulation.md, "Moving obstacles").
     */
    template <int dim> class ObstacleMotion
    {
    public:
      /**
       * @p translation: d(t), dim components, evaluated at the origin;
       * @p rotation: θ(t), the angle (rad, counter-clockwise) in 2D and the
       * rotation vector (axis times angle, rad) in 3D, or null for none;
       * @p centre: c, the point the obstacle turns about, at rest.
       */
      ObstacleMotion(std::shared_ptr<Function<dim>> translation,
                     std::shared_ptr<Function<dim>> rotation,
                     const Point<dim>              &centre)
          : translation(std::move(translation))
          , rotation(std::move(rotation))
          , centre(centre)
      {
      }

      /** @brief The obstacle's position at time @p t. */
      RigidMotion<dim>
      at(const double t) const;

      /**
       * @brief The rotation centre, as far from the bodies as it may be: the
       * turned obstacle's points are c + R (x − c), which carry a round-off of
       * about 1e-16 |x − c|, and that must stay below the contact's touching
       * tolerance, 1e-12 of the bodies' diameter. A centre farther than
       * centre_reach diameters from @p body_point (a point of the bodies)
       * throws an InputError naming `Obstacle/Motion/Rotation centre`.
       */
      void
      check_centre(const Point<dim> &body_point, double body_diameter) const;

      /** How many bodies' diameters the rotation centre may lie from them. */
      static constexpr double centre_reach = 1e4;

      /** @brief True when the obstacle turns (its normals change with time). */
      bool
      rotates() const
      {
        return rotation != nullptr;
      }

    private:
      std::shared_ptr<Function<dim>> translation;
      std::shared_ptr<Function<dim>> rotation;
      Point<dim>                     centre;
    };

    /**
     * @brief A rigid analytic obstacle (an `Obstacle` plug-in) as the contact
     * partner: smooth, without DoFs, fixed in space or moved by a rigid
     * motion (ObstacleMotion).
     */
    template <int dim> class RigidObstacle : public Partner<dim>
    {
    public:
      /**
       * @p motion: the obstacle's rigid motion, or null for a fixed obstacle;
       * until set_time() the obstacle is where the motion puts it at t = 0.
       */
      explicit RigidObstacle(const Obstacles::Interface<dim>           &obstacle,
                             std::shared_ptr<const ObstacleMotion<dim>> motion = nullptr)
          : obstacle(obstacle)
          , motion(std::move(motion))
      {
        set_time(0., 0.);
      }

      /**
       * The moved obstacle's pairing: that of the obstacle at rest with the
       * point the motion takes to x, moved by the motion (n, t_α and their
       * gradients turned by R).
       */
      Pairing<dim>
      project(const Point<dim> &x) const override;

      void
      set_time(const double start, const double now) override
      {
        if (motion)
          {
            motion_start = motion->at(start);
            motion_now   = motion->at(now);
          }
      }

      /** A turning plane's normal changes from step to step: it is paired anew. */
      bool
      is_flat() const override
      {
        return obstacle.is_flat() && !(motion && motion->rotates());
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
       * The frozen pairing moved with the obstacle since it was made; the slip
       * is relative to the obstacle: Δu² is where the obstacle's motion over
       * the step takes the slave point's start position, minus that position.
       */
      Tensor<1, dim>
      follow(Pairing<dim> &pairing,
             const TrilinosWrappers::MPI::Vector &,
             const TrilinosWrappers::MPI::Vector &,
             const Point<dim> &slave_start) const override;

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
      const Obstacles::Interface<dim>           &obstacle;
      std::shared_ptr<const ObstacleMotion<dim>> motion;
      RigidMotion<dim>                           motion_start, motion_now;
      const IndexSet                             no_dofs;
      const std::vector<unsigned int>            no_faces;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
