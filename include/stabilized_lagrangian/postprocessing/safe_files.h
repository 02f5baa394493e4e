#pragma once

#include <string>

namespace StabilizedLagrangian
{
  /**
   * Output that a run killed at any moment leaves whole: a file is either its
   * previous or its new content, and a CSV ends with a whole row.
   */
  namespace SafeFiles
  {
    /**
     * @brief Write @p content to @p path through a temporary file in the same
     * directory, renamed over @p path once complete (rename is atomic on POSIX
     * file systems).
     */
    void
    write_atomically(const std::string &path, const std::string &content);

    /**
     * @brief Append @p content (whole rows) to @p path in one write(2) call on a
     * file opened with O_APPEND, so a kill leaves either all of it or none.
     */
    void
    append(const std::string &path, const std::string &content);

    /**
     * @brief Cut @p path to its first @p size bytes (the rows a checkpoint
     * knows of); a file shorter than that, or whose byte @p size − 1 is not
     * the newline that ends a row, is an error (it was not the run's).
     */
    void
    truncate(const std::string &path, const unsigned long size);

    /**
     * @brief Why a write into @p directory may have failed, for messages: "no
     * space left on the device" when its file system is (nearly) full, else
     * "not writable, or an input/output error".
     */
    std::string
    free_space_note(const std::string &directory);
  } // namespace SafeFiles
} // namespace StabilizedLagrangian
