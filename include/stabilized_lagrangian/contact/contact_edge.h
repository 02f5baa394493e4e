#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief The pressure near the end of a contact zone between smooth bodies,
     * fitted to the points of one face that holds it, for the pressure
     * estimate (doc/formulation.md, "Error estimate").
     *
     * Where smooth elastic bodies separate, the pressure falls to zero like a
     * square root of the distance d to the edge of the contact zone, and the
     * gap opens like its power 3/2 (the local field of a Hertz contact, Johnson
     * 1985 §4.2; the same in 3D, across a smooth edge):
     *
     *   p = c √d  inside,    g = (4 c / 3E*) (−d)^{3/2}  outside,
     *
     * E* the plane-strain modulus of the pair (1/E* = Σ (1 − ν²)/E over the
     * deformable bodies). The face's points in contact give d = (λ_n / c)², its
     * open points d = −(3 E* g / 4c)^{2/3}; d is affine along the face (the
     * edge a straight line across it) with |∇d| = 1, which fixes c. Neither a
     * linear λ_n nor any polynomial follows the square root inside the face;
     * this model does, so ‖p − λ_n‖ on such a face is read from it.
     */
    template <int dim> class SquareRootOnset
    {
    public:
      /** No fit (a face that holds no end of the contact zone). */
      SquareRootOnset() = default;

      /**
       * Fit to @p points of a face with outward unit normal @p normal: at each,
       * whether it is in contact, λ_n and the gap g. No fit (valid() false)
       * when all points are in contact, or all open, or the fit fails.
       */
      SquareRootOnset(const std::vector<Point<dim>> &points,
                      const std::vector<bool>       &in_contact,
                      const std::vector<double>     &pressures,
                      const std::vector<double>     &gaps,
                      const Tensor<1, dim>          &normal,
                      double                         modulus);

      bool
      valid() const
      {
        return fitted;
      }

      /** The model's pressure c √d⁺ at @p x on the face. */
      double
      pressure(const Point<dim> &x) const;

      /** The signed distance d at @p x (positive in contact). */
      double
      distance(const Point<dim> &x) const;

    private:
      Point<dim>     origin;
      Tensor<1, dim> gradient;
      double         offset = 0.;
      double         c      = 0.;
      bool           fitted = false;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
