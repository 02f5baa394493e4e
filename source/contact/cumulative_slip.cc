#include <stabilized_lagrangian/contact/cumulative_slip.h>

#include <cmath>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  CumulativeSlip<dim>::commit(const unsigned int step, std::vector<ContactSample<dim>> &samples)
  {
    for (auto &sample : samples)
      {
        const auto &k = sample.kinematics;
        // the step's slip, as the slip_increment output field shows it
        const Tensor<1, dim> increment = sample.state.pairing.from_tangential_components(
            sample.state.pairing.tangential_components(k.step_increment));
        const AtNode &node     = add(Point<dim>(k.position - k.displacement),
                                 increment,
                                 sample.response.status() != Contact::Status::open,
                                 step);
        sample.cumulative_slip = node.total;
        sample.slip_path       = node.path;
      }
  }

  template <int dim>
  const typename CumulativeSlip<dim>::AtNode &
  CumulativeSlip<dim>::add(const Point<dim>     &X,
                           const Tensor<1, dim> &increment,
                           const bool            in_contact,
                           const unsigned int    step)
  {
    // a node is sampled once per face that holds it: each sample of a step
    // sets the same total from the value before the step
    std::array<std::int64_t, dim> key;
    for (unsigned int d = 0; d < dim; ++d)
      key[d] = std::llround(X[d] * 1e9);
    AtNode &slip = nodes[key];
    if (slip.step != step)
      {
        slip.before      = slip.total;
        slip.path_before = slip.path;
        slip.step        = step;
      }
    slip.total = slip.before + (in_contact ? increment : Tensor<1, dim>());
    slip.path  = slip.path_before + (in_contact ? increment.norm() : 0.);
    return slip;
  }

  template <int dim>
  std::vector<double>
  CumulativeSlip<dim>::list() const
  {
    // per node of Γc: key, step, then the sums
    std::vector<double> slips;
    for (const auto &[key, slip] : nodes)
      {
        slips.insert(slips.end(), key.begin(), key.end());
        slips.push_back(slip.step);
        for (const Tensor<1, dim> *sum : {&slip.before, &slip.total})
          for (unsigned int d = 0; d < dim; ++d)
            slips.push_back((*sum)[d]);
        slips.push_back(slip.path_before);
        slips.push_back(slip.path);
      }
    return slips;
  }

  template <int dim>
  void
  CumulativeSlip<dim>::restore(const std::vector<double> &slips)
  {
    nodes.clear();
    const unsigned int entry = 3 * dim + 3;
    for (std::size_t i = 0; i < slips.size(); i += entry)
      {
        const double                 *values = slips.data() + i;
        std::array<std::int64_t, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = static_cast<std::int64_t>(values[d]);
        AtNode &slip = nodes[key];
        slip.step    = static_cast<unsigned int>(values[dim]);
        for (unsigned int d = 0; d < dim; ++d)
          {
            slip.before[d] = values[dim + 1 + d];
            slip.total[d]  = values[2 * dim + 1 + d];
          }
        slip.path_before = values[3 * dim + 1];
        slip.path        = values[3 * dim + 2];
      }
  }

  template class CumulativeSlip<2>;
  template class CumulativeSlip<3>;
} // namespace StabilizedLagrangian
