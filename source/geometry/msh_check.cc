// The checks of an ASCII Gmsh .msh file (format 2 or 4) before GridIn reads
// it: its sections, counts, node and element references, and its physical
// names; every error names the file, the line and what is allowed.

#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/geometry/msh_check.h>
#include <stabilized_lagrangian/plugins.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    using namespace dealii;

    namespace
    {
      /** Number of nodes of the Gmsh element types a mesh of this program may hold. */
      const std::map<int, unsigned int> element_nodes = {
          {1, 2}, {2, 3}, {3, 4}, {4, 4}, {5, 8}, {6, 6}, {7, 5}, {15, 1}};

      /**
       * @brief An ASCII .msh file (format 2 or 4) checked before GridIn reads it:
       * GridIn trusts the counts and references of the file, and a truncated,
       * binary or inconsistent file makes it read past the end, abort or accept
       * garbage. Every error names the file, the line and what is allowed.
       */
      class MshScanner
      {
      public:
        explicit MshScanner(const std::string &file)
            : file(file)
        {
          std::ifstream in(file, std::ios::binary);
          if (!in)
            fail(0, "cannot be opened");
          std::string line;
          while (std::getline(in, line))
            {
              if (line.find('\0') != std::string::npos)
                fail(lines.size() + 1,
                     "holds binary data; write the mesh as ASCII (Gmsh option "
                     "Mesh.Binary = 0)");
              lines.push_back(Utilities::trim(line));
            }
          check_sections();
          const unsigned int format = section("$MeshFormat", true);
          std::istringstream header(line_at(format + 1));
          double             version   = 0.;
          int                file_type = -1;
          if (!(header >> version >> file_type))
            fail(format + 2, "a $MeshFormat line must read 'version file-type data-size'");
          if (!((version >= 2. && version < 3.) || (version >= 4. && version < 5.)))
            fail(
                format + 2,
                "format version " + line_at(format + 1).substr(0, line_at(format + 1).find(' ')) +
                    " is not supported; write format 2.2 or 4.1 (Gmsh option Mesh.MshFileVersion)");
          if (file_type != 0)
            fail(format + 2,
                 "is a binary .msh file; write it as ASCII (Gmsh option Mesh.Binary = 0)");
          v4 = version >= 4.;
          read_physical_names();
          read_nodes();
          read_elements();
        }

        /** (dimension, name) → tag of the physical groups. */
        std::map<std::pair<int, std::string>, int> physical_groups;

      private:
        [[noreturn]] void
        fail(const std::size_t line, const std::string &what) const
        {
          throw InputError("Geometry/gmsh/Mesh file: '" + file + "'" +
                           (line > 0 ? " line " + std::to_string(line) : std::string()) + ": " +
                           what + ".");
        }

        const std::string &
        line_at(const std::size_t index) const
        {
          if (index >= lines.size())
            fail(lines.size(), "the file ends early (truncated?)");
          return lines[index];
        }

        /** Every $Section is closed by its $EndSection before the next one opens. */
        void
        check_sections() const
        {
          std::string open;
          std::size_t opened = 0;
          for (std::size_t i = 0; i < lines.size(); ++i)
            if (!lines[i].empty() && lines[i][0] == '$')
              {
                if (lines[i].rfind("$End", 0) == 0)
                  {
                    if (lines[i] != "$End" + open.substr(1))
                      fail(i + 1, lines[i] + " closes no open section");
                    open.clear();
                  }
                else if (!open.empty())
                  fail(opened + 1,
                       "section " + open + " is not closed by $End" + open.substr(1) +
                           " (truncated or edited file?)");
                else
                  open = lines[i], opened = i;
              }
          if (!open.empty())
            fail(opened + 1,
                 "section " + open + " is not closed by $End" + open.substr(1) +
                     " (truncated file?)");
          if (lines.empty())
            fail(0, "is empty");
        }

        /** Index of the line "$name", or lines.size() when optional and absent. */
        std::size_t
        section(const std::string &name, const bool required) const
        {
          for (std::size_t i = 0; i < lines.size(); ++i)
            if (lines[i] == name)
              return i;
          if (required)
            fail(0, "has no " + name + " section (not a Gmsh mesh?)");
          return lines.size();
        }

        /** The integers or reals of line @p index: at least @p at_least, and nothing else. */
        template <typename T>
        std::vector<T>
        numbers(const std::size_t index, const std::size_t at_least, const std::string &what) const
        {
          std::istringstream in(line_at(index));
          std::vector<T>     result;
          T                  value;
          while (in >> value)
            result.push_back(value);
          in.clear();
          std::string rest;
          if (in >> rest || result.size() < at_least)
            fail(index + 1, "expected " + what + ", got '" + lines[index] + "'");
          return result;
        }

        std::size_t
        count(const std::size_t index, const std::string &what) const
        {
          const auto values = numbers<long long>(index, 1, what);
          if (values[0] < 0 || values[0] > static_cast<long long>(lines.size()))
            fail(index + 1,
                 what + " " + std::to_string(values[0]) + " is negative or larger than the file");
          return static_cast<std::size_t>(values[0]);
        }

        void
        expect_end(const std::size_t  index,
                   const std::string &name,
                   const std::string &counted) const
        {
          if (line_at(index) != name)
            fail(index + 1,
                 "expected " + name + " after the " + counted +
                     " announced by the section's count, got '" + lines[index] + "'");
        }

        void
        read_physical_names()
        {
          const std::size_t start = section("$PhysicalNames", false);
          if (start == lines.size())
            return;
          const std::size_t n = count(start + 1, "number of physical names");
          for (std::size_t i = start + 2; i < start + 2 + n; ++i)
            {
              std::istringstream in(line_at(i));
              int                dimension = -1, tag = -1;
              const auto         first = lines[i].find('"'), last = lines[i].rfind('"');
              if (!(in >> dimension >> tag) || dimension < 0 || dimension > 3 ||
                  first == std::string::npos || last <= first)
                fail(i + 1,
                     "a physical name reads 'dimension tag \"name\"', got '" + lines[i] + "'");
              physical_groups[{dimension, lines[i].substr(first + 1, last - first - 1)}] = tag;
            }
          expect_end(start + 2 + n, "$EndPhysicalNames", "physical names");
        }

        void
        add_node(const std::size_t index, const long long tag, const std::vector<double> &xyz)
        {
          for (const double x : xyz)
            if (!std::isfinite(x))
              fail(index + 1, "node " + std::to_string(tag) + " has a non-finite coordinate");
          if (!node_tags.insert(tag).second)
            fail(index + 1, "node " + std::to_string(tag) + " is defined twice");
        }

        /**
         * Read the required section $@p name, of @p things, and check its
         * counts: in format 2 a count and that many records, each read by
         * @p read_record(line); in format 4 a header 'blocks total min-tag
         * max-tag' and the blocks, each read by @p read_block(its header, as
         * @p block_header describes it; the line after it, moved past the
         * block), which returns the block's size; the sizes must add up to
         * the total.
         */
        template <typename ReadRecord, typename ReadBlock>
        void
        read_section(const std::string &name,
                     const std::string &things,
                     const std::string &block_header,
                     const ReadRecord  &read_record,
                     const ReadBlock   &read_block)
        {
          const std::size_t start = section("$" + name, true);
          std::size_t       i     = start + 1;
          if (!v4)
            {
              const std::size_t n = count(i++, "number of " + things);
              for (std::size_t k = 0; k < n; ++k, ++i)
                read_record(i);
            }
          else
            {
              const auto header =
                  numbers<long long>(i++, 4, "'blocks " + things + " min-tag max-tag'");
              std::size_t total = 0;
              for (long long block = 0; block < header[0]; ++block)
                {
                  const auto b = numbers<long long>(i++, 4, block_header);
                  if (b[3] < 0 || b[3] > static_cast<long long>(lines.size()))
                    fail(i,
                         things.substr(0, things.size() - 1) + " block of " + std::to_string(b[3]) +
                             " " + things + ": larger than the file");
                  total += read_block(b, i);
                }
              if (static_cast<long long>(total) != header[1])
                fail(start + 2,
                     "announces " + std::to_string(header[1]) + " " + things +
                         ", the blocks hold " + std::to_string(total));
            }
          expect_end(i, "$End" + name, things);
        }

        void
        read_nodes()
        {
          read_section(
              "Nodes",
              "nodes",
              "'dimension entity parametric nodes'",
              [&](const std::size_t i) {
                const auto v = numbers<double>(i, 4, "'tag x y z'");
                add_node(i, static_cast<long long>(v[0]), {v[1], v[2], v[3]});
              },
              [&](const std::vector<long long> &b, std::size_t &i) {
                // a block lists its node tags, then their coordinates
                const std::size_t n    = static_cast<std::size_t>(b[3]);
                const std::size_t tags = i;
                for (std::size_t k = 0; k < n; ++k)
                  {
                    const auto v = numbers<double>(tags + n + k, 3, "'x y z'");
                    add_node(tags + n + k,
                             numbers<long long>(tags + k, 1, "a node tag")[0],
                             {v[0], v[1], v[2]});
                  }
                i = tags + 2 * n;
                return n;
              });
        }

        void
        add_element(const std::size_t index, const int type, const std::vector<long long> &nodes)
        {
          const auto known = element_nodes.find(type);
          if (known == element_nodes.end())
            fail(index + 1,
                 "element type " + std::to_string(type) +
                     " is not supported: lines (1), triangles (2), quadrilaterals (3), "
                     "tetrahedra (4), hexahedra (5) and points (15), i.e. first-order "
                     "elements");
          if (nodes.size() != known->second)
            fail(index + 1,
                 "an element of type " + std::to_string(type) + " has " +
                     std::to_string(known->second) + " nodes, this one " +
                     std::to_string(nodes.size()));
          for (const long long node : nodes)
            if (node_tags.count(node) == 0)
              fail(index + 1,
                   "the element refers to node " + std::to_string(node) +
                       ", which $Nodes does not define");
        }

        void
        read_elements()
        {
          read_section(
              "Elements",
              "elements",
              "'dimension entity type elements'",
              [&](const std::size_t i) {
                const auto v = numbers<long long>(i, 3, "'tag type n-tags tags... nodes...'");
                if (v[2] < 0 || static_cast<std::size_t>(v[2]) + 3 > v.size())
                  fail(i + 1, "the element announces more tags than the line holds");
                add_element(i,
                            static_cast<int>(v[1]),
                            std::vector<long long>(v.begin() + 3 + v[2], v.end()));
              },
              [&](const std::vector<long long> &b, std::size_t &i) {
                for (long long k = 0; k < b[3]; ++k, ++i)
                  {
                    const auto v = numbers<long long>(i, 2, "'tag nodes...'");
                    add_element(
                        i, static_cast<int>(b[2]), std::vector<long long>(v.begin() + 1, v.end()));
                  }
                return static_cast<std::size_t>(b[3]);
              });
        }

        const std::string        file;
        std::vector<std::string> lines;
        bool                     v4 = false;
        std::set<long long>      node_tags;
      };
    } // namespace

    std::map<std::pair<int, std::string>, int>
    check_msh_file(const std::string &file)
    {
      return MshScanner(file).physical_groups;
    }
  } // namespace Geometry
} // namespace StabilizedLagrangian
