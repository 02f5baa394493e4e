// ok/FAIL reporting shared by the unit tests.

#pragma once

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace CheckTools
{
  /** The text of the file @p path (a scene to which a test appends its `set`s). */
  inline std::string
  file_text(const std::string &path)
  {
    std::ifstream      file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
  }

  /**
   * The elastic patin of prm/patin_elastic.prm (@p prm_dir: prm/) on a coarse
   * mesh (2 refinements), for a test to append its `set`s to (a later `set` of
   * an entry replaces the file's).
   */
  inline std::string
  coarse_patin(const std::string &prm_dir)
  {
    return file_text(prm_dir + "/patin_elastic.prm") + R"(
subsection Geometry
  subsection block
    set Global refinements = 2
  end
end
)";
  }

  /** Number of failed checks so far. */
  inline int failures = 0;

  /** Print an ok/FAIL line and count a failure. */
  inline void
  check(const bool ok, const std::string &what, const double value)
  {
    std::cout << (ok ? "ok    " : "FAIL  ") << what << ": " << value << std::endl;
    failures += !ok;
  }

  /** check() that an error is below its tolerance, printing the error. */
  inline void
  check_below(const double error, const double tolerance, const std::string &what)
  {
    check(error < tolerance, what, error);
  }

  /** Print the closing line and return the exit code of the test. */
  inline int
  summary()
  {
    std::cout << (failures ? "FAILED" : "PASSED") << std::endl;
    return failures ? EXIT_FAILURE : EXIT_SUCCESS;
  }
} // namespace CheckTools
