#pragma once

#include <map>
#include <string>
#include <utility>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    /**
     * @brief Check the ASCII Gmsh mesh @p file (format 2 or 4) before GridIn
     * reads it, and return its physical groups, (dimension, name) → tag.
     *
     * GridIn trusts the counts and references of the file, and a truncated,
     * binary or inconsistent file makes it read past the end, abort or accept
     * garbage: the sections, the counts, the node and element references and
     * the element types are checked here, and every InputError names the
     * file (as `Geometry/gmsh/Mesh file`), the line and what is allowed.
     */
    std::map<std::pair<int, std::string>, int>
    check_msh_file(const std::string &file);
  } // namespace Geometry
} // namespace StabilizedLagrangian
