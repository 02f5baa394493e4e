#include <stabilized_lagrangian/contact/friction_law_check.h>

#include <boost/serialization/utility.hpp>

#include <algorithm>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    template <int dim>
    FrictionLawCheck<dim>::FrictionLawCheck(const double largest_displacement)
        : length_scale(largest_displacement)
    {
    }

    template <int dim>
    void
    FrictionLawCheck<dim>::add_multiplier_row(const bool normal, const double length)
    {
      (normal ? gap_lengths : slip_lengths).push_back(length);
    }

    template <int dim>
    void
    FrictionLawCheck<dim>::add_point(const Point<dim> &where,
                                     const double      traction,
                                     const double      threshold)
    {
      largest_threshold   = std::max(largest_threshold, threshold);
      const double excess = std::max(traction - threshold, 0.);
      traction_excesses.push_back(excess);
      if (excess > worst_excess)
        {
          worst_excess    = excess;
          worst_excess_at = where;
        }
    }

    template <int dim>
    unsigned int
    FrictionLawCheck<dim>::gather(const MPI_Comm communicator, const double traction_tolerance)
    {
      const double allowed_length =
          length_tolerance * Utilities::MPI::max(length_scale, communicator);
      const double allowed_traction =
          traction_tolerance * Utilities::MPI::max(largest_threshold, communicator);
      const auto count_above = [](const std::vector<double> &values, const double allowed) {
        return static_cast<unsigned int>(std::count_if(
            values.begin(), values.end(), [&](const double v) { return v > allowed; }));
      };
      const auto largest = [&](const std::vector<double> &values) {
        return Utilities::MPI::max(
            values.empty() ? 0. : *std::max_element(values.begin(), values.end()), communicator);
      };
      const unsigned int gaps =
          Utilities::MPI::sum(count_above(gap_lengths, allowed_length), communicator);
      const unsigned int slips =
          Utilities::MPI::sum(count_above(slip_lengths, allowed_length), communicator);
      const unsigned int tractions =
          Utilities::MPI::sum(count_above(traction_excesses, allowed_traction), communicator);
      const double worst_gap  = largest(gap_lengths);
      const double worst_slip = largest(slip_lengths);
      // the largest traction excess over all ranks, with its place
      const auto excesses =
          Utilities::MPI::all_gather(communicator, std::make_pair(worst_excess, worst_excess_at));
      const auto worst =
          *std::max_element(excesses.begin(), excesses.end(), [](const auto &a, const auto &b) {
            return a.first < b.first;
          });

      text.clear();
      if (gaps + slips + tractions == 0)
        return 0;
      std::ostringstream message;
      message << "the converged state breaks the contact law it reports:";
      if (gaps > 0)
        message << ' ' << gaps << " contact equation(s) miss by up to " << worst_gap
                << " mm (a gap or penetration where the point is in contact);";
      if (slips > 0)
        message << ' ' << slips << " friction equation(s) miss by up to " << worst_slip
                << " mm (a slip where the point sticks);";
      if (gaps + slips > 0)
        message << " allowed: " << allowed_length << " mm, " << length_tolerance
                << " of the largest displacement;";
      if (tractions > 0)
        message << ' ' << tractions << " point(s) with |t_t| above s = mu lambda_n, by up to "
                << worst.first << " MPa at (" << worst.second << "), allowed " << allowed_traction
                << " MPa;";
      text        = message.str();
      text.back() = '.';
      return gaps + slips + tractions;
    }

    template <int dim>
    const std::string &
    FrictionLawCheck<dim>::report() const
    {
      return text;
    }

    template class FrictionLawCheck<2>;
    template class FrictionLawCheck<3>;
  } // namespace Contact
} // namespace StabilizedLagrangian
