#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/parameters.h>

#include <gmsh.h>

#include <filesystem>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <thread>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
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

        void
        read_nodes()
        {
          const std::size_t start = section("$Nodes", true);
          std::size_t       i     = start + 1;
          if (!v4)
            {
              const std::size_t n = count(i++, "number of nodes");
              for (std::size_t k = 0; k < n; ++k, ++i)
                {
                  const auto v = numbers<double>(i, 4, "'tag x y z'");
                  add_node(i, static_cast<long long>(v[0]), {v[1], v[2], v[3]});
                }
            }
          else
            {
              const auto  header = numbers<long long>(i++, 4, "'blocks nodes min-tag max-tag'");
              std::size_t total  = 0;
              for (long long block = 0; block < header[0]; ++block)
                {
                  const auto b = numbers<long long>(i++, 4, "'dimension entity parametric nodes'");
                  if (b[3] < 0 || b[3] > static_cast<long long>(lines.size()))
                    fail(i,
                         "node block of " + std::to_string(b[3]) + " nodes: larger than the file");
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
                  total += n;
                }
              if (static_cast<long long>(total) != header[1])
                fail(start + 2,
                     "announces " + std::to_string(header[1]) + " nodes, the blocks hold " +
                         std::to_string(total));
            }
          expect_end(i, "$EndNodes", "nodes");
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
          const std::size_t start = section("$Elements", true);
          std::size_t       i     = start + 1;
          if (!v4)
            {
              const std::size_t n = count(i++, "number of elements");
              for (std::size_t k = 0; k < n; ++k, ++i)
                {
                  const auto v = numbers<long long>(i, 3, "'tag type n-tags tags... nodes...'");
                  if (v[2] < 0 || static_cast<std::size_t>(v[2]) + 3 > v.size())
                    fail(i + 1, "the element announces more tags than the line holds");
                  add_element(i,
                              static_cast<int>(v[1]),
                              std::vector<long long>(v.begin() + 3 + v[2], v.end()));
                }
            }
          else
            {
              const auto  header = numbers<long long>(i++, 4, "'blocks elements min-tag max-tag'");
              std::size_t total  = 0;
              for (long long block = 0; block < header[0]; ++block)
                {
                  const auto b = numbers<long long>(i++, 4, "'dimension entity type elements'");
                  if (b[3] < 0 || b[3] > static_cast<long long>(lines.size()))
                    fail(i,
                         "element block of " + std::to_string(b[3]) +
                             " elements: larger than the file");
                  for (long long k = 0; k < b[3]; ++k, ++i)
                    {
                      const auto v = numbers<long long>(i, 2, "'tag nodes...'");
                      add_element(i,
                                  static_cast<int>(b[2]),
                                  std::vector<long long>(v.begin() + 1, v.end()));
                    }
                  total += static_cast<std::size_t>(b[3]);
                }
              if (static_cast<long long>(total) != header[1])
                fail(start + 2,
                     "announces " + std::to_string(header[1]) + " elements, the blocks hold " +
                         std::to_string(total));
            }
          expect_end(i, "$EndElements", "elements");
        }

        const std::string        file;
        std::vector<std::string> lines;
        bool                     v4 = false;
        std::set<long long>      node_tags;
      };

      /**
       * Mesh a .geo file with the Gmsh library into a .msh file (format 2.2),
       * in a child process: a .geo is a program (loops, `Exit;`, meshes of any
       * size), so the meshing gets @p seconds of wall time and @p memory_mib of
       * address space, and a Gmsh that exits or crashes ends only the child.
       */
      void
      mesh_geo_file(const std::string &geo_file,
                    const std::string &msh_file,
                    const int          dim,
                    const double       seconds,
                    const double       memory_mib)
      {
        const std::string entry = "Geometry/gmsh/Mesh file: '" + geo_file + "'";
        std::filesystem::remove(msh_file);
        const pid_t child = ::fork();
        if (child < 0)
          throw InputError(entry + ": cannot start the meshing process.");
        if (child == 0)
          {
            // the MPI library's crash handlers belong to the parent
            for (const int signal_number : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL})
              ::signal(signal_number, SIG_DFL);
            const rlim_t bytes = static_cast<rlim_t>(memory_mib * 1024. * 1024.);
            const rlimit limit{bytes, bytes};
            ::setrlimit(RLIMIT_AS, &limit);
            int status = 0;
            try
              {
                gmsh::initialize();
                gmsh::option::setNumber("General.Terminal", 0);
                gmsh::open(geo_file);
                gmsh::model::mesh::generate(dim);
                gmsh::option::setNumber("Mesh.MshFileVersion", 2.2);
                gmsh::write(msh_file);
                gmsh::finalize();
              }
            catch (...)
              {
                status = 3;
              }
            ::_exit(status);
          }
        int        status = 0;
        const auto start  = std::chrono::steady_clock::now();
        while (::waitpid(child, &status, WNOHANG) == 0)
          {
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
                seconds)
              {
                ::kill(child, SIGKILL);
                ::waitpid(child, &status, 0);
                std::filesystem::remove(msh_file);
                throw InputError(entry + ": Gmsh did not finish meshing within " +
                                 Utilities::to_string(seconds) +
                                 " s (Geometry/gmsh/Meshing time limit): an endless loop, or a "
                                 "mesh far finer than intended?");
              }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
        if (WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0))
          {
            std::filesystem::remove(msh_file);
            throw InputError(entry + ": Gmsh could not mesh it" +
                             (WIFSIGNALED(status)
                                  ? " (it was stopped by signal " +
                                        std::to_string(WTERMSIG(status)) +
                                        "; out of the memory allowed by Geometry/gmsh/Meshing "
                                        "memory limit?)"
                                  : std::string(" (a syntax error or a geometry it cannot mesh)")) +
                             ".");
          }
        if (!std::filesystem::exists(msh_file))
          throw InputError(entry + ": Gmsh stopped without writing a mesh (an `Exit;` in the "
                                   "file?).");
      }
    } // namespace

    /**
     * @brief A mesh from Gmsh: a .msh file, or a .geo file meshed by the Gmsh
     * library at start-up. Its physical groups name the boundaries (dimension
     * dim − 1, their tags become boundary ids) and the bodies (dimension dim,
     * material ids), so the `Boundary conditions` and `Contact` entries can
     * refer to them by name. The cells are quadrilaterals / hexahedra
     * (`Recombine` in Gmsh) or triangles / tetrahedra, not both.
     */
    template <int dim> class GmshMesh : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "A .msh file (format 2 or 4, ASCII) or a .geo file, meshed by the "
                          "Gmsh library when the run starts; a relative path is looked up in "
                          "the working directory, then beside the parameter file.");
        prm.declare_entry(
            "Global refinements", "0", Patterns::Integer(0, 12), "Uniform refinements.");
        prm.declare_entry(
            "Spherical boundaries",
            "",
            Patterns::Anything(),
            "Boundaries that lie on a sphere (3D) or a circle (2D), as `boundary: centre` "
            "separated by `;` (e.g. `contact: 0, 0, 50; master: 0, -100`), the boundary by "
            "its physical group's name or id. Refinement places the new vertices of these "
            "faces on the sphere, so a refined mesh converges to the curved surface "
            "instead of keeping the facets of the coarse one. The boundary's vertices must "
            "be equidistant from the centre (to 1e-6 of the radius).");
        prm.declare_entry("Meshing time limit",
                          "300",
                          Patterns::Double(1.),
                          "Wall time (s) Gmsh may take to mesh a .geo file before the run is "
                          "stopped with an error (a .geo is a program: it may loop).");
        prm.declare_entry("Meshing memory limit",
                          "8192",
                          Patterns::Double(64.),
                          "Address space (MiB) Gmsh may use to mesh a .geo file.");
      }

      GmshMesh(const ParameterHandler &prm, const std::string &section)
          : section(section)
          , file(Parameters::input_path(prm.get("Mesh file")))
          , refinements(prm.get_integer("Global refinements"))
      {
        if (file.empty() || !std::filesystem::is_regular_file(file))
          throw InputError(section + "/Mesh file: cannot open '" + file + "'.");
        const std::string extension = std::filesystem::path(file).extension();
        if (extension != ".msh" && extension != ".geo")
          throw InputError(section + "/Mesh file: '" + file +
                           "' is neither a .msh nor a .geo file.");
        std::string msh_file = file;
        if (extension == ".geo")
          {
            // every rank meshes its own copy: the .geo is small and Gmsh is deterministic
            msh_file = (std::filesystem::temp_directory_path() /
                        ("stabilized_lagrangian_" + std::to_string(::getpid()) + "_" +
                         std::filesystem::path(file).stem().string() + ".msh"))
                           .string();
            mesh_geo_file(file,
                          msh_file,
                          dim,
                          prm.get_double("Meshing time limit"),
                          prm.get_double("Meshing memory limit"));
          }
        read_mesh(msh_file);
        if (msh_file != file)
          std::filesystem::remove(msh_file);
        read_spherical_boundaries(prm.get("Spherical boundaries"));
      }

      bool
      simplex_cells() const override
      {
        return simplex;
      }

      void
      create_mesh(Triangulation<dim> &triangulation) const override
      {
        triangulation.copy_triangulation(coarse);
        // manifold id k + 1 for the k-th sphere (0 would be the cells' default flat one)
        for (unsigned int k = 0; k < spheres.size(); ++k)
          {
            for (const auto &face : triangulation.active_face_iterators())
              if (face->at_boundary() && face->boundary_id() == spheres[k].first)
                face->set_all_manifold_ids(k + 1);
            triangulation.set_manifold(k + 1, SphericalManifold<dim>(spheres[k].second));
          }
        triangulation.refine_global(refinements);
      }

      std::map<std::string, types::boundary_id>
      boundary_names() const override
      {
        return boundaries;
      }

      std::map<std::string, types::material_id>
      body_names() const override
      {
        return bodies;
      }

    private:
      /** The coarse mesh and the names of its physical groups. */
      void
      read_mesh(const std::string &msh_file)
      {
        for (const auto &[key, tag] : MshScanner(msh_file).physical_groups)
          if (key.first == dim)
            bodies[key.second] = static_cast<types::material_id>(tag);
          else
            boundaries[key.second] = static_cast<types::boundary_id>(tag);
        GridIn<dim> grid_in;
        grid_in.attach_triangulation(coarse);
        std::ifstream in(msh_file);
        try
          {
            grid_in.read_msh(in);
          }
        catch (const ExceptionBase &error)
          {
            std::ostringstream message;
            error.print_info(message);
            throw InputError(section + "/Mesh file: cannot read '" + file +
                             "' as a Gmsh mesh: " + Utilities::trim(message.str()));
          }
        unsigned int n_simplices = 0;
        for (const auto &cell : coarse.active_cell_iterators())
          {
            if (!cell->reference_cell().is_hyper_cube() && !cell->reference_cell().is_simplex())
              throw InputError(section + "/Mesh file: '" + file + "' has " +
                               cell->reference_cell().to_string() +
                               " cells; the mesh must be made of quadrilaterals or hexahedra, "
                               "or of triangles or tetrahedra.");
            n_simplices += cell->reference_cell().is_simplex();
          }
        simplex = n_simplices > 0;
        if (simplex && n_simplices != coarse.n_active_cells())
          throw InputError(section + "/Mesh file: '" + file + "' mixes " +
                           std::to_string(n_simplices) + " simplices with " +
                           std::to_string(coarse.n_active_cells() - n_simplices) +
                           " hypercube cells; the finite element pairs need one cell shape "
                           "(all triangles/tetrahedra, or all quadrilaterals/hexahedra: "
                           "Recombine in Gmsh).");
      }

      /**
       * Parse `Spherical boundaries` and check that each boundary's vertices
       * are on one sphere around its centre: a wrong centre would move the
       * refined vertices off the body's surface and distort the cells.
       */
      void
      read_spherical_boundaries(const std::string &text)
      {
        const std::string entry = section + "/Spherical boundaries";
        for (const std::string &item : Utilities::split_string_list(text, ';'))
          {
            const auto colon = item.find(':');
            if (colon == std::string::npos)
              throw InputError(entry + ": '" + item +
                               "' is not `boundary: centre` (e.g. `contact: 0, 0, 50`).");
            const std::string name        = Utilities::trim(item.substr(0, colon));
            const auto        coordinates = Utilities::split_string_list(item.substr(colon + 1));
            Point<dim>        center;
            try
              {
                AssertThrow(coordinates.size() == dim, ExcMessage(""));
                for (unsigned int d = 0; d < dim; ++d)
                  center[d] = Utilities::string_to_double(coordinates[d]);
              }
            catch (...)
              {
                throw InputError(entry + ": the centre of '" + name + "' must be " +
                                 std::to_string(dim) + " numbers separated by commas, not '" +
                                 Utilities::trim(item.substr(colon + 1)) + "'.");
              }
            spheres.emplace_back(boundary_id(entry, name), center);
            check_on_sphere(entry, name, spheres.back());
          }
      }

      /** The boundary id of a physical group's name or id. */
      types::boundary_id
      boundary_id(const std::string &entry, const std::string &name) const
      {
        if (const auto named = boundaries.find(name); named != boundaries.end())
          return named->second;
        std::string known;
        for (const auto &[group, id] : boundaries)
          {
            known += (known.empty() ? "" : ", ") + group;
            if (name == std::to_string(id))
              return id;
          }
        throw InputError(entry + ": '" + file + "' has no boundary '" + name +
                         "'; its boundaries: " + (known.empty() ? "none" : known) + ".");
      }

      void
      check_on_sphere(const std::string                               &entry,
                      const std::string                               &name,
                      const std::pair<types::boundary_id, Point<dim>> &sphere) const
      {
        double smallest = std::numeric_limits<double>::max(), largest = 0.;
        for (const auto &face : coarse.active_face_iterators())
          if (face->at_boundary() && face->boundary_id() == sphere.first)
            for (const unsigned int v : face->vertex_indices())
              {
                const double distance = face->vertex(v).distance(sphere.second);
                smallest              = std::min(smallest, distance);
                largest               = std::max(largest, distance);
              }
        if (largest == 0.)
          throw InputError(entry + ": the boundary '" + name + "' has no face in '" + file + "'.");
        if (largest - smallest > 1e-6 * largest)
          throw InputError(entry + ": the vertices of the boundary '" + name +
                           "' are not on one sphere around the given centre: their distances "
                           "to it range from " +
                           std::to_string(smallest) + " to " + std::to_string(largest) + " mm.");
      }

      const std::string                                      section; ///< for messages
      const std::string                                      file;
      const unsigned int                                     refinements;
      Triangulation<dim>                                     coarse;
      bool                                                   simplex = false;
      std::vector<std::pair<types::boundary_id, Point<dim>>> spheres;
      std::map<std::string, types::boundary_id>              boundaries;
      std::map<std::string, types::material_id>              bodies;
    };

    SL_REGISTER_PLUGIN(
        Interface,
        GmshMesh,
        "gmsh",
        "a Gmsh mesh (.msh or .geo) whose physical groups name boundaries and bodies");
  } // namespace Geometry
} // namespace StabilizedLagrangian
