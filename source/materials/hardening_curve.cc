#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/materials/hardening_curve.h>
#include <stabilized_lagrangian/plugins.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    namespace
    {
      std::string
      to_string(const double value)
      {
        std::ostringstream stream;
        stream << value;
        return stream.str();
      }

      double
      parse_number(const std::string &text, const std::string &pair, const std::string &entry_path)
      {
        std::size_t end   = 0;
        double      value = 0.;
        const auto  fail  = [&]() {
          throw InputError(entry_path + ": cannot read a number from '" + text + "' in '" + pair +
                           "'; expected 'plastic strain:yield stress' pairs separated by ','.");
        };
        try
          {
            value = std::stod(text, &end);
          }
        catch (const std::exception &)
          {
            fail();
          }
        if (end != text.size() || !std::isfinite(value))
          fail();
        return value;
      }
    } // namespace

    HardeningCurve::HardeningCurve(const std::vector<std::pair<double, double>> &points_in,
                                   const std::string                            &entry_path)
        : points(points_in)
    {
      if (points.empty())
        throw InputError(entry_path + " needs at least one 'plastic strain:yield stress' pair.");
      if (points.front().first != 0.)
        throw InputError(entry_path + ": the first plastic strain must be 0, got " +
                         to_string(points.front().first) + ".");
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          if (!(points[i].second > 0.) || !std::isfinite(points[i].second))
            throw InputError(entry_path + ": yield stresses must be > 0, got " +
                             to_string(points[i].second) + " at plastic strain " +
                             to_string(points[i].first) + ".");
          if (i == 0)
            continue;
          if (!(points[i].first > points[i - 1].first) || !std::isfinite(points[i].first))
            throw InputError(entry_path + ": plastic strains must be strictly increasing, got " +
                             to_string(points[i].first) + " after " +
                             to_string(points[i - 1].first) + ".");
          if (points[i].second < points[i - 1].second)
            throw InputError(entry_path + ": yield stresses must be non-decreasing, got " +
                             to_string(points[i].second) + " after " +
                             to_string(points[i - 1].second) + ".");
        }
    }

    std::vector<std::pair<double, double>>
    HardeningCurve::parse(const std::string &text, const std::string &entry_path)
    {
      std::vector<std::pair<double, double>> points;
      for (const std::string &pair : dealii::Utilities::split_string_list(text, ','))
        {
          const std::vector<std::string> values = dealii::Utilities::split_string_list(pair, ':');
          if (values.size() != 2)
            throw InputError(entry_path + ": '" + pair +
                             "' is not a 'plastic strain:yield stress' pair.");
          points.emplace_back(parse_number(values[0], pair, entry_path),
                              parse_number(values[1], pair, entry_path));
        }
      return points;
    }

    unsigned int
    HardeningCurve::segment(const double alpha) const
    {
      if (points.size() < 2)
        return 0;
      // first point with α_i > α, minus one; clamped to the first and last segments
      const auto above = std::upper_bound(
          points.begin(),
          points.end(),
          alpha,
          [](const double a, const std::pair<double, double> &p) { return a < p.first; });
      const long index = static_cast<long>(above - points.begin()) - 1;
      return static_cast<unsigned int>(
          std::clamp<long>(index, 0, static_cast<long>(points.size()) - 2));
    }

    double
    HardeningCurve::hardening_modulus(const double alpha) const
    {
      if (points.size() < 2)
        return 0.;
      const unsigned int i = segment(alpha);
      return (points[i + 1].second - points[i].second) / (points[i + 1].first - points[i].first);
    }

    double
    HardeningCurve::yield_stress(const double alpha) const
    {
      const unsigned int i = segment(alpha);
      return points[i].second + hardening_modulus(alpha) * (alpha - points[i].first);
    }
  } // namespace Materials
} // namespace StabilizedLagrangian
