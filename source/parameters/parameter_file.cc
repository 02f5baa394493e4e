// The parameter file with its includes expanded (parameters/parameter_file.h):
// every file read is checked to be a text file of reasonable size, and every
// chain of includes to end.

#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/parameters/parameter_file.h>
#include <stabilized_lagrangian/plugins.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    using namespace dealii;

    namespace
    {
      /** A parameter file larger than this is not one (a device, a log, a mesh). */
      constexpr std::uintmax_t max_parameter_file_size = std::uintmax_t(16) << 20;
      /** Deeper include chains than this are refused (a cycle is caught before). */
      constexpr unsigned int max_include_depth = 32;

      /**
       * The content of the text file @p filename: refused with a message when it
       * is missing, a directory, a device, FIFO or socket (reading would block or
       * never end), larger than max_parameter_file_size, or binary.
       */
      std::string
      read_text_file(const std::string &filename, const std::string &what)
      {
        namespace fs = std::filesystem;
        std::error_code ec;
        const auto      status = fs::status(filename, ec);
        if (!fs::exists(status))
          throw InputError(what + " '" + filename + "' does not exist.");
        if (fs::is_directory(status))
          throw InputError(what + " '" + filename + "' is a directory, not a parameter file.");
        if (!fs::is_regular_file(status))
          throw InputError(what + " '" + filename +
                           "' is not a regular file (a device, FIFO or socket): give a "
                           "parameter file.");
        if (fs::file_size(filename, ec) > max_parameter_file_size)
          throw InputError(what + " '" + filename + "' is larger than " +
                           std::to_string(max_parameter_file_size >> 20) +
                           " MiB: not a parameter file.");
        std::ifstream file(filename, std::ios::binary);
        if (!file)
          throw InputError("Cannot open " + what + " '" + filename + "' (permissions?).");
        std::stringstream content;
        content << file.rdbuf();
        const std::string text = content.str();
        if (const auto nul = text.find('\0'); nul != std::string::npos)
          throw InputError("'" + filename + "' line " +
                           std::to_string(std::count(text.begin(), text.begin() + nul, '\n') + 1) +
                           ": " + what +
                           " contains NUL bytes (the first here): a binary file, not a parameter "
                           "file; a parameter file holds text only.");
        return text;
      }

      /** The file named by an `include` (or `INCLUDE`) line, or nothing. */
      std::optional<std::string>
      included_file(const std::string &line)
      {
        std::string statement = line.substr(0, line.find('#'));
        statement             = Utilities::trim(statement);
        for (const std::string keyword : {"include", "INCLUDE"})
          if (statement.rfind(keyword, 0) == 0 &&
              (statement.size() == keyword.size() ||
               std::isspace(static_cast<unsigned char>(statement[keyword.size()]))))
            return Utilities::trim(statement.substr(keyword.size()));
        return std::nullopt;
      }

      /**
       * A `set Mesh file = <path>` line whose relative path does not exist from
       * the working directory, with the path beside @p filename, the file that
       * holds the line: a scene included from another folder keeps its meshes.
       */
      std::string
      path_beside_file(const std::string &line, const std::string &filename)
      {
        namespace fs = std::filesystem;
        static const std::regex mesh_file(R"(^(\s*set\s+Mesh file\s*=\s*)([^#]*[^#\s])(.*)$)");
        std::smatch             match;
        if (!std::regex_match(line, match, mesh_file))
          return line;
        const std::string path = match[2].str();
        if (fs::path(path).is_absolute() || fs::exists(path))
          return line;
        return match[1].str() + (fs::path(filename).parent_path() / path).string() + match[3].str();
      }

      /**
       * Expand the `include` lines of @p filename recursively (each included
       * file as given if it exists, else beside the including file; a relative
       * mesh file likewise, path_beside_file()), refusing a
       * file that includes itself, directly or not, and chains deeper than
       * max_include_depth.
       */
      void
      expand(const std::string &filename, std::vector<std::string> &chain, ExpandedFile &out)
      {
        namespace fs           = std::filesystem;
        const std::string what = chain.empty() ? "The parameter file" : "The included file";
        const std::string text = read_text_file(filename, what);
        std::error_code   ec;
        const std::string canonical = fs::weakly_canonical(filename, ec).string();
        if (std::find(chain.begin(), chain.end(), canonical) != chain.end())
          {
            std::string cycle;
            for (const auto &file : chain)
              cycle += file + " -> ";
            throw InputError("The parameter file includes itself: " + cycle + canonical + ".");
          }
        if (chain.size() >= max_include_depth)
          throw InputError("More than " + std::to_string(max_include_depth) +
                           " nested include statements, at '" + filename + "'.");
        chain.push_back(canonical);
        std::istringstream lines(text);
        std::string        line;
        for (unsigned int number = 1; std::getline(lines, line); ++number)
          if (const auto include = included_file(line))
            {
              if (include->empty())
                throw InputError("'" + filename + "' line " + std::to_string(number) +
                                 ": an include statement without a file name.");
              std::string path = *include;
              if (!fs::path(path).is_absolute() && !fs::exists(path))
                path = (fs::path(filename).parent_path() / path).string();
              expand(path, chain, out);
            }
          else
            {
              out.text += path_beside_file(line, filename) + "\n";
              out.origin.emplace_back(filename, number);
            }
        chain.pop_back();
      }

    } // namespace

    /** The parameter file @p filename expanded; refused if it sets no parameter. */
    ExpandedFile
    read_file(const std::string &filename)
    {
      ExpandedFile             result;
      std::vector<std::string> chain;
      expand(filename, chain, result);
      if (!std::regex_search(result.text, std::regex("(^|\n)[ \t]*set[ \t]")))
        throw InputError("The parameter file '" + filename +
                         "' sets no parameter (an empty file?). Run the program without a "
                         "file for the built-in scene.");
      return result;
    }
  } // namespace Parameters
} // namespace StabilizedLagrangian
