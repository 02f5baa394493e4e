#include <deal.II/physics/transformations.h>

#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/plugins.h>

#include <sstream>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    namespace
    {
      /**
       * Turn the pairing's normal by @p R: the tangents are those of the turned
       * normal (tangent_basis(), as for an obstacle at rest, so that Λ keeps
       * its basis), the gradients turn as ∂n/∂x = R (∂n/∂X) Rᵀ.
       */
      template <int dim>
      void
      turn(Pairing<dim> &pairing, const Tensor<2, dim> &R)
      {
        pairing.normal          = R * pairing.normal;
        pairing.tangents        = tangent_basis(pairing.normal);
        pairing.normal_gradient = R * pairing.normal_gradient * transpose(R);
        const auto dt_dn        = tangent_basis_derivative(pairing.normal);
        for (unsigned int a = 0; a < dim - 1; ++a)
          pairing.tangent_gradients[a] = dt_dn[a] * pairing.normal_gradient;
      }
    } // namespace

    template <int dim>
    void
    ObstacleMotion<dim>::check_centre(const Point<dim> &body_point,
                                      const double      body_diameter) const
    {
      const double distance = centre.distance(body_point);
      if (!(distance <= centre_reach * body_diameter))
        {
          std::ostringstream message;
          message << "Obstacle/Motion/Rotation centre = " << centre << " lies " << distance
                  << " mm from the bodies, more than " << centre_reach << " times their diameter ("
                  << body_diameter
                  << " mm): the obstacle's turned points would carry round-off larger than "
                     "the contact's touching tolerance (1e-12 of the diameter). Give a centre "
                     "within "
                  << centre_reach * body_diameter << " mm of the bodies.";
          throw InputError(message.str());
        }
    }

    template <int dim>
    RigidMotion<dim>
    ObstacleMotion<dim>::at(const double t) const
    {
      RigidMotion<dim> motion;
      motion.centre = centre;
      if (translation)
        {
          translation->set_time(t);
          for (unsigned int c = 0; c < dim; ++c)
            motion.translation[c] = translation->value(Point<dim>(), c);
        }
      if (rotation)
        {
          rotation->set_time(t);
          if constexpr (dim == 2)
            motion.rotation = Physics::Transformations::Rotations::rotation_matrix_2d(
                rotation->value(Point<dim>()));
          else
            {
              Tensor<1, 3> vector;
              for (unsigned int c = 0; c < 3; ++c)
                vector[c] = rotation->value(Point<dim>(), c);
              const double angle = vector.norm();
              if (angle > 0.)
                motion.rotation =
                    Physics::Transformations::Rotations::rotation_matrix_3d(vector / angle, angle);
            }
        }
      return motion;
    }

    template <int dim>
    Pairing<dim>
    RigidObstacle<dim>::project(const Point<dim> &x) const
    {
      Pairing<dim> pairing = obstacle.project(motion_now.inverse(x));
      pairing.master_point = motion_now.apply(pairing.master_point);
      if (motion && motion->rotates())
        turn(pairing, motion_now.rotation);
      pairing.partner_motion = motion_now;
      return pairing;
    }

    template <int dim>
    Tensor<1, dim>
    RigidObstacle<dim>::follow(Pairing<dim> &pairing,
                               const TrilinosWrappers::MPI::Vector &,
                               const TrilinosWrappers::MPI::Vector &,
                               const Point<dim> &slave_start) const
    {
      pairing.master_point = motion_now.apply(pairing.partner_motion.inverse(pairing.master_point));
      if (motion && motion->rotates())
        turn(pairing, motion_now.rotation * transpose(pairing.partner_motion.rotation));
      pairing.partner_motion = motion_now;
      return motion_now.apply(motion_start.inverse(slave_start)) - slave_start;
    }

    template class ObstacleMotion<2>;
    template class ObstacleMotion<3>;
    template class RigidObstacle<2>;
    template class RigidObstacle<3>;
  } // namespace Contact
} // namespace StabilizedLagrangian
