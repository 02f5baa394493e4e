// Whole numbers of the input read without the standard library's conversions,
// which throw a bare "stoul" at a number too large for their type.

#include <stabilized_lagrangian/parameters.h>

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    std::optional<unsigned long long>
    decimal_integer(const std::string &text, const unsigned long long max)
    {
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
      unsigned long long value = 0;
      for (const char digit : text)
        {
          const auto next = static_cast<unsigned long long>(digit - '0');
          if (next > max || value > (max - next) / 10)
            return std::nullopt;
          value = 10 * value + next;
        }
      return value;
    }
  } // namespace Parameters
} // namespace StabilizedLagrangian
