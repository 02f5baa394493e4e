// The Gmsh geometry plug-in: a .msh file, or a .geo file meshed by the Gmsh
// library in a child process, read into the coarse mesh with its physical
// groups as boundary and body names, and its spherical boundaries. The
// checks of the .msh file before it is read are in msh_check.cc.

#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/geometry/msh_check.h>
#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/parameters.h>

#include <gmsh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
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
      /**
       * Mesh a .geo file with the Gmsh library into a .msh file (format 2.2),
       * in a child process: a .geo is a program (loops, `Exit;`, meshes of any
       * size), so the meshing gets @p seconds of wall time and @p memory_mib of
       * address space, and a Gmsh that exits or crashes ends only the child.
       */
      /** The child's exit code for a geometry of dimension d: this + d. */
      constexpr int geometry_dimension_status = 10;

      /** What is wrong with a geometry of dimension @p model_dim in a run of dimension @p dim. */
      std::string
      other_dimension(const int model_dim, const int dim)
      {
        const std::string entities = model_dim == 3   ? "volumes"
                                     : model_dim == 2 ? "surfaces"
                                                      : "curves";
        return "its geometry is " +
               (model_dim == 0
                    ? std::string("empty (no point, curve, surface or volume)")
                    : std::to_string(model_dim) + "D (its highest entities are " + entities + ")") +
               ", and the run is " + std::to_string(dim) + "D (Dimension = " + std::to_string(dim) +
               "). Set `Dimension = " + std::to_string(std::clamp(model_dim, 2, 3)) +
               "` at the top of the parameter file, or give a " + std::to_string(dim) +
               "D geometry.";
      }

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
                // a geometry of another dimension than the run's: the exit
                // code carries it to the parent's message
                const int model_dim = gmsh::model::getDimension();
                if (model_dim != dim)
                  ::_exit(geometry_dimension_status + std::max(model_dim, 0));
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
        if (WIFEXITED(status) && WEXITSTATUS(status) >= geometry_dimension_status &&
            WEXITSTATUS(status) <= geometry_dimension_status + 3)
          {
            throw InputError(entry + ": " +
                             other_dimension(WEXITSTATUS(status) - geometry_dimension_status, dim));
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
                          "the working directory, then beside the parameter file that sets "
                          "it (an included file's meshes beside it).");
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
        this->refine_global(triangulation, refinements);
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
        for (const auto &[key, tag] : check_msh_file(msh_file))
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
