#include <stabilized_lagrangian/postprocessing/safe_files.h>

#include <fcntl.h>
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
      {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        file << content;
        file.close();
        if (!file)
          fail("write", temporary);
      }
      std::filesystem::rename(temporary, path);
    }

    void
    append(const std::string &path, const std::string &content)
    {
      const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
      if (fd < 0)
        fail("open", path);
      // a regular file takes the whole buffer in one call unless the disk is full
      const ssize_t written = ::write(fd, content.data(), content.size());
      const bool    whole   = written == static_cast<ssize_t>(content.size());
      ::close(fd);
      if (!whole)
        fail("append to", path);
    }

    void
    truncate(const std::string &path, const unsigned long size)
    {
      if (std::filesystem::file_size(path) < size)
        throw std::runtime_error(path + " is shorter than the checkpoint says (" +
                                 std::to_string(size) + " bytes): not the file of this run");
      std::filesystem::resize_file(path, size);
    }
  } // namespace SafeFiles
} // namespace StabilizedLagrangian
