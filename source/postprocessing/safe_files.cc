#include <stabilized_lagrangian/postprocessing/safe_files.h>

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace StabilizedLagrangian
{
  namespace SafeFiles
  {
    namespace
    {
      [[noreturn]] void
      fail(const std::string &what, const std::string &path)
      {
        throw std::runtime_error("cannot " + what + " " + path + ": " + std::strerror(errno));
      }
    } // namespace

    void
    write_atomically(const std::string &path, const std::string &content)
    {
      const std::string temporary = path + ".tmp";
      const int         fd        = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0)
        fail("write", temporary);
      const ssize_t written = ::write(fd, content.data(), content.size());
      const int     error   = errno;
      const bool    whole   = written == static_cast<ssize_t>(content.size()) && ::close(fd) == 0;
      if (!whole)
        {
          // a full disk: the old file stays as it was, the partial copy goes
          ::unlink(temporary.c_str());
          errno = written < 0 || error != 0 ? error : ENOSPC;
          fail("write", path);
        }
      std::filesystem::rename(temporary, path);
    }

    void
    append(const std::string &path, const std::string &content)
    {
      const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
      if (fd < 0)
        fail("open", path);
      // a regular file takes the whole buffer in one call unless the disk is
      // full; then the part written is cut off again, so the file keeps whole rows
      const off_t   size    = ::lseek(fd, 0, SEEK_END);
      const ssize_t written = ::write(fd, content.data(), content.size());
      const int     error   = written < 0 ? errno : ENOSPC;
      const bool    whole   = written == static_cast<ssize_t>(content.size());
      if (!whole && size >= 0) [[maybe_unused]]
        const int ignored = ::ftruncate(fd, size);
      ::close(fd);
      if (!whole)
        {
          errno = error;
          fail("append to", path);
        }
    }

    std::string
    free_space_note(const std::string &directory)
    {
      struct statvfs fs;
      if (::statvfs(directory.c_str(), &fs) == 0)
        {
          const unsigned long long free_bytes =
              static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize;
          // less than a block left: the write that failed found the disk full
          if (free_bytes < 64 * 1024ull)
            return "no space left on the device (" + std::to_string(free_bytes) + " bytes free)";
        }
      return "the directory is not writable, or an input/output error occurred";
    }

    void
    truncate(const std::string &path, const unsigned long size)
    {
      if (std::filesystem::file_size(path) < size)
        throw std::runtime_error(path + " is shorter than the checkpoint says (" +
                                 std::to_string(size) + " bytes): not the file of this run");
      // the rows a checkpoint knows of end with a newline: a cut inside a row
      // would leave half of one
      char last = '\n';
      if (size > 0)
        {
          std::ifstream file(path, std::ios::binary);
          file.seekg(static_cast<std::streamoff>(size - 1));
          file.get(last);
        }
      if (last != '\n')
        throw std::runtime_error(path + " has no row ending at byte " + std::to_string(size) +
                                 ", where the checkpoint says its rows end: not the file of "
                                 "this run, or a damaged checkpoint");
      std::filesystem::resize_file(path, size);
    }
  } // namespace SafeFiles
} // namespace StabilizedLagrangian
