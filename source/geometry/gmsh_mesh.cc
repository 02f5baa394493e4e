#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/parameters.h>

#include <gmsh.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    namespace
    {
      /** Physical groups of a .msh file: (dimension, name) → tag, from $PhysicalNames. */
      std::map<std::pair<int, std::string>, int>
      read_physical_names(const std::string &msh_file)
      {
        std::map<std::pair<int, std::string>, int> groups;
        std::ifstream                              in(msh_file);
        std::string                                line;
        while (std::getline(in, line))
          if (Utilities::trim(line) == "$PhysicalNames")
            {
              unsigned int n = 0;
              in >> n;
              for (unsigned int i = 0; i < n; ++i)
                {
                  int dimension = 0, tag = 0;
                  in >> dimension >> tag;
                  std::getline(in, line);
                  const auto first = line.find('"'), last = line.rfind('"');
                  if (first != std::string::npos && last > first)
                    groups[{dimension, line.substr(first + 1, last - first - 1)}] = tag;
                }
              break;
            }
        return groups;
      }

      /** Mesh a .geo file with the Gmsh library into a .msh file (format 2.2). */
      void
      mesh_geo_file(const std::string &geo_file, const std::string &msh_file, const int dim)
      {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        try
          {
            gmsh::open(geo_file);
            gmsh::model::mesh::generate(dim);
            gmsh::option::setNumber("Mesh.MshFileVersion", 2.2);
            gmsh::write(msh_file);
          }
        catch (...)
          {
            gmsh::finalize();
            throw InputError("Geometry/gmsh/Mesh file: Gmsh could not mesh '" + geo_file + "'.");
          }
        gmsh::finalize();
      }
    } // namespace

    /**
     * @brief A mesh from Gmsh: a .msh file, or a .geo file meshed by the Gmsh
     * library at start-up. Its physical groups name the boundaries (dimension
     * dim − 1, their tags become boundary ids) and the bodies (dimension dim,
     * material ids), so the `Boundary conditions` and `Contact` entries can
     * refer to them by name. The cells must be quadrilaterals / hexahedra
     * (`Recombine` in Gmsh).
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
      }

      explicit GmshMesh(const ParameterHandler &prm)
          : file(Parameters::input_path(prm.get("Mesh file")))
          , refinements(prm.get_integer("Global refinements"))
      {
        if (file.empty() || !std::filesystem::is_regular_file(file))
          throw InputError("Geometry/gmsh/Mesh file: cannot open '" + file + "'.");
        const std::string extension = std::filesystem::path(file).extension();
        if (extension != ".msh" && extension != ".geo")
          throw InputError("Geometry/gmsh/Mesh file: '" + file +
                           "' is neither a .msh nor a .geo file.");
        std::string msh_file = file;
        if (extension == ".geo")
          {
            // every rank meshes its own copy: the .geo is small and Gmsh is deterministic
            msh_file = (std::filesystem::temp_directory_path() /
                        ("stabilized_lagrangian_" + std::to_string(::getpid()) + "_" +
                         std::filesystem::path(file).stem().string() + ".msh"))
                           .string();
            mesh_geo_file(file, msh_file, dim);
          }
        read_mesh(msh_file);
        if (msh_file != file)
          std::filesystem::remove(msh_file);
      }

      void
      create_mesh(parallel::distributed::Triangulation<dim> &triangulation) const override
      {
        triangulation.copy_triangulation(coarse);
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
        for (const auto &[key, tag] : read_physical_names(msh_file))
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
        catch (const std::exception &error)
          {
            throw InputError("Geometry/gmsh/Mesh file: cannot read '" + file +
                             "' as a Gmsh mesh: " + Utilities::trim(error.what()));
          }
        for (const auto &cell : coarse.active_cell_iterators())
          if (!cell->reference_cell().is_hyper_cube())
            throw InputError("Geometry/gmsh/Mesh file: '" + file +
                             "' has simplex cells; the finite elements need quadrilaterals or "
                             "hexahedra (Recombine in Gmsh).");
      }

      const std::string                         file;
      const unsigned int                        refinements;
      Triangulation<dim>                        coarse;
      std::map<std::string, types::boundary_id> boundaries;
      std::map<std::string, types::material_id> bodies;
    };

    namespace
    {
      template <int dim>
      bool
      register_gmsh()
      {
        return Registry<dim>::add(
            "gmsh",
            "a Gmsh mesh (.msh or .geo) whose physical groups name boundaries and bodies",
            &GmshMesh<dim>::declare_parameters,
            [](const ParameterHandler &prm) -> std::unique_ptr<Interface<dim>> {
              return std::make_unique<GmshMesh<dim>>(prm);
            });
      }
      const bool registered_2d = register_gmsh<2>();
      const bool registered_3d = register_gmsh<3>();
    } // namespace
  }   // namespace Geometry
} // namespace StabilizedLagrangian
