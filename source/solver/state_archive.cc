#include <stabilized_lagrangian/solver/state_archive.h>

#include <algorithm>
#include <cmath>

namespace StabilizedLagrangian
{
  std::uint64_t
  state_checksum(const std::string_view bytes)
  {
    std::uint64_t hash = 14695981039346656037ull;
    for (const unsigned char byte : bytes)
      hash = (hash ^ byte) * 1099511628211ull;
    return hash;
  }

  bool
  is_decimal_number(const std::string &text, const std::size_t longest)
  {
    return !text.empty() && text.size() <= longest &&
           text.find_first_not_of("0123456789") == std::string::npos;
  }

  void
  throw_damaged_checkpoint(const std::string &path, const std::string &what)
  {
    throw InputError("the checkpoint file " + path + " is damaged: " + what +
                     ". Start the run again without --resume, or resume from an intact copy "
                     "of the checkpoint.");
  }

  std::string
  StateWriter::sealed() const
  {
    std::string         text = out.str();
    const std::uint64_t sum  = state_checksum(text);
    text.append(reinterpret_cast<const char *>(&sum), sizeof(sum));
    return text;
  }

  StateReader::StateReader(std::string data, std::string path)
      : data(std::move(data))
      , path(std::move(path))
      , end(this->data.size())
  {
  }

  std::vector<double>
  StateReader::get_finite(const std::string &what, const std::size_t expected)
  {
    std::vector<double> values;
    get(values, what);
    if (expected != std::string::npos && values.size() != expected)
      damaged("it has " + std::to_string(values.size()) + " " + what + ", the rebuilt mesh " +
              std::to_string(expected));
    if (!std::all_of(values.begin(), values.end(), [](const double x) { return std::isfinite(x); }))
      damaged("its " + what + " are not all finite");
    return values;
  }

  void
  StateReader::get(std::string &text, const std::size_t longest, const std::string &what)
  {
    const std::uint64_t size = count(what, 1);
    if (size > longest)
      damaged(what + " is " + std::to_string(size) + " characters long, at most " +
              std::to_string(longest) + " are valid");
    text.resize(size);
    take(text.data(), size);
  }

  std::uint64_t
  StateReader::count(const std::string &what, const std::size_t item_bytes)
  {
    std::uint64_t n = 0;
    get(n);
    if (n > (end - position) / std::max<std::size_t>(item_bytes, 1))
      damaged("the count of " + what + " is " + std::to_string(n) + ", more than the " +
              std::to_string(end - position) + " bytes left can hold");
    return n;
  }

  void
  StateReader::check_sum()
  {
    std::uint64_t stored = 0;
    if (data.size() < position + sizeof(stored))
      truncated();
    std::memcpy(&stored, data.data() + data.size() - sizeof(stored), sizeof(stored));
    end = data.size() - sizeof(stored);
    if (stored != state_checksum(std::string_view(data).substr(0, end)))
      damaged("its checksum does not match its content (a byte was changed, or the file was "
              "cut or extended)");
  }

  void
  StateReader::damaged(const std::string &what) const
  {
    throw_damaged_checkpoint(path, what);
  }

  void
  StateReader::take(void *destination, const std::size_t size)
  {
    if (size > end - position)
      truncated();
    // (an empty vector's data() may be null, which memcpy may not be given)
    if (size > 0)
      std::memcpy(destination, data.data() + position, size);
    position += size;
  }

  void
  StateReader::truncated() const
  {
    throw InputError("the checkpoint file " + path +
                     " is truncated or damaged: it ends before its data does.");
  }
} // namespace StabilizedLagrangian
