#pragma once

#include <stabilized_lagrangian/plugins.h>

#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace StabilizedLagrangian
{
  /**
   * @brief FNV-1a (64 bits) of @p bytes: the last 8 bytes of a checkpoint's
   * rank file, so that a changed byte or a cut is found before any of its
   * fields is used.
   */
  std::uint64_t
  state_checksum(const std::string_view bytes);

  /**
   * @brief Binary writer of trivially copyable values and vectors of them:
   * the bytes of the run's state (RunState), for a step cut in memory and for
   * a checkpoint on disk.
   */
  class StateWriter
  {
  public:
    /** @brief Append the bytes of @p value. */
    template <typename T>
    void
    put(const T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      out.write(reinterpret_cast<const char *>(&value), sizeof(T));
    }
    /** @brief Append the size of @p values, then their bytes. */
    template <typename T>
    void
    put(const std::vector<T> &values)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      put(static_cast<std::uint64_t>(values.size()));
      out.write(reinterpret_cast<const char *>(values.data()), values.size() * sizeof(T));
    }
    /** @brief Append the length of @p text, then its characters. */
    void
    put(const std::string &text)
    {
      put(std::vector<char>(text.begin(), text.end()));
    }
    /** @brief The bytes written. */
    std::string
    bytes() const
    {
      return out.str();
    }
    /** @brief The bytes written, followed by their checksum (state_checksum()). */
    std::string
    sealed() const;

  private:
    std::ostringstream out;
  };

  /**
   * @brief The reader of StateWriter's format, for untrusted bytes: every
   * count is checked against the bytes left before anything is allocated,
   * every string against its longest valid length; a read past the end means a
   * truncated file. Whatever does not fit throws an InputError naming the file.
   */
  class StateReader
  {
  public:
    /**
     * @param data the bytes to read
     * @param path the file they come from, named by the messages
     */
    StateReader(std::string data, std::string path);
    /** @brief The next value. */
    template <typename T>
    void
    get(T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      take(&value, sizeof(T));
    }
    /** @brief The next vector; @p what names its items in a message. */
    template <typename T>
    void
    get(std::vector<T> &values, const std::string &what)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      values.resize(count(what, sizeof(T)));
      take(values.data(), values.size() * sizeof(T));
    }
    /**
     * @brief The next list of values, all finite; with @p expected (not
     * `std::string::npos`), exactly that many: a damaged file otherwise.
     * @p what names the values in a message.
     */
    std::vector<double>
    get_finite(const std::string &what, const std::size_t expected = std::string::npos);
    /** @brief The next string, of at most @p longest characters. */
    void
    get(std::string &text, const std::size_t longest, const std::string &what);
    /** @brief A count of items of at least @p item_bytes bytes each: no more than the bytes left
     * hold. */
    std::uint64_t
    count(const std::string &what, const std::size_t item_bytes);
    /** @brief Check the last 8 bytes against the checksum of the others, all that is read. */
    void
    check_sum();
    /** @brief Whether every byte was read. */
    bool
    at_end() const
    {
      return position == end;
    }
    /** @brief Throw the InputError of a damaged file, saying @p what is wrong. */
    [[noreturn]] void
    damaged(const std::string &what) const;
    /** @brief The file the bytes come from. */
    const std::string &
    file() const
    {
      return path;
    }

  private:
    void
    take(void *destination, const std::size_t size);
    [[noreturn]] void
                      truncated() const;
    const std::string data;
    const std::string path;
    std::size_t       end;
    std::size_t       position = 0;
  };

  /** @brief Whether @p text is 1 to @p longest decimal digits. */
  bool
  is_decimal_number(const std::string &text, const std::size_t longest);

  /**
   * @brief The InputError of the damaged checkpoint file @p path, saying
   * @p what is wrong and how to go on.
   */
  [[noreturn]] void
  throw_damaged_checkpoint(const std::string &path, const std::string &what);
} // namespace StabilizedLagrangian
