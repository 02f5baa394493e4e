#pragma once

#include <string>
#include <utility>
#include <vector>

/**
 * @file
 * A parameter file as the parser reads it: its `include` lines expanded, each
 * line with the file and line it came from (for the messages), its relative
 * mesh paths resolved beside the file that holds them.
 */

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    /** @brief A parameter file with its includes expanded, and where each line came from. */
    struct ExpandedFile
    {
      std::string                                   text;
      std::vector<std::pair<std::string, unsigned>> origin; // (file, line) of each line
    };

    /**
     * @brief The parameter file @p filename with its includes expanded;
     * refused (InputError) if it, or a file it includes, is missing, not a
     * text file, includes itself, or if it sets no parameter.
     */
    ExpandedFile
    read_file(const std::string &filename);
  } // namespace Parameters
} // namespace StabilizedLagrangian
