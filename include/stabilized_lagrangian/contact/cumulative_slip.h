#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>

#include <array>
#include <cstdint>
#include <map>
#include <vector>

/**
 * @file
 * The converged state at the nodes of Γc, sampled once per accepted load
 * step, and the slip accumulated over the steps from those samples: the
 * solver commits it, the output reads it.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The converged state at one node of Γc (a node of one contact face:
   * a node shared by two faces is sampled once from each), as the output and
   * the cumulative slip read it.
   */
  template <int dim> struct ContactSample
  {
    typename Triangulation<dim>::cell_iterator cell; ///< the contact face's cell
    unsigned int                               face_no;
    Point<dim>                                 reference_position; ///< X
    ContactPointState<dim>                     state; ///< evaluated afresh at the iterate
    ContactKinematics<dim>                     kinematics;
    Contact::PointResponse<dim - 1>            response; ///< the point-wise stabilized Lagrangian
    double                                     gap;      ///< g_n with the point's pairing
    /** the slip accumulated at the node up to this step (CumulativeSlip::commit) */
    Tensor<1, dim> cumulative_slip;
    double         slip_path = 0.; ///< the sum of the steps' slip lengths
  };

  /**
   * @brief The slip accumulated at each node of Γc over the converged steps in
   * which it was in contact: the vector sum of the steps' slip increments and
   * the sum of their lengths (the slip path). Part of the run's state (a
   * checkpoint keeps it); cleared when a load path starts.
   */
  template <int dim> class CumulativeSlip
  {
  public:
    /**
     * @brief Add the slip of the converged step @p step at every sample of
     * @p samples (the step's increment where the sample is not open) and
     * write the node's accumulated slip into the sample. A node sampled from
     * several faces has each sample's increment added to its value before the
     * step, so the last sample's is the one kept.
     */
    void
    commit(unsigned int step, std::vector<ContactSample<dim>> &samples);

    /** @brief Forget every node's slip (a new load path). */
    void
    clear()
    {
      nodes.clear();
    }

    /** @brief Per node: its key, its step, then the sums, as restore() reads them. */
    std::vector<double>
    list() const;

    /** @brief The slips of list(). */
    void
    restore(const std::vector<double> &slips);

  private:
    /** The slip of one node, up to the end of step `step`. */
    struct AtNode
    {
      unsigned int   step = 0; ///< the last step added
      Tensor<1, dim> before;   ///< the vector sum before that step
      double         path_before = 0.;
      Tensor<1, dim> total; ///< the vector sum with it
      double         path = 0.;
    };

    /** the node at reference position @p X, its slip brought to @p step (seed: before + Δ) */
    const AtNode &
    add(const Point<dim> &X, const Tensor<1, dim> &increment, bool in_contact, unsigned int step);

    /** by reference position, in 1e-9 mm */
    std::map<std::array<std::int64_t, dim>, AtNode> nodes;
  };
} // namespace StabilizedLagrangian
