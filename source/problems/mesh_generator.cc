/**
 * @file
 * The mesh generators of 'Geometry/Mesh': `subdivided box` (GridGenerator)
 * and `file` (GridIn), and the family's defaults.
 */

#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <perideal/base/exceptions.h>
#include <perideal/problems/mesh_generator.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    std::optional<typename MeshGenerator<dim>::CoarseSize>
    MeshGenerator<dim>::coarse_size() const
    {
      return std::nullopt;
    }


    template <int dim>
    std::vector<IO::OutputName>
    MeshGenerator<dim>::input_names() const
    {
      return {};
    }


    template <int dim>
    void
    MeshGenerator<dim>::declare_parameters(ParameterHandler &)
    {}


    template <int dim>
    std::string
    MeshGenerator<dim>::family_name()
    {
      return "mesh";
    }


    template <int dim>
    std::string
    mesh_generator_pattern(const std::string &default_name)
    {
      std::string pattern = default_name;
      for (const auto &name : MeshGeneratorRegistry<dim>::names())
        if (name != default_name)
          pattern += "|" + name;
      return pattern;
    }


    namespace
    {
      template <int dim>
      Point<dim>
      parse_point(const std::string &text)
      {
        const auto values =
          Utilities::string_to_double(Utilities::split_string_list(text));
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = values[d];
        return p;
      }


      /**
       * The box between 'Lower corner' and 'Upper corner' with
       * 'Subdivisions' cells per direction, boundary ids by face (0/1 on
       * x = min/max, 2/3 on y, 4/5 on z).
       */
      template <int dim>
      class SubdividedBox : public MeshGenerator<dim>
      {
      public:
        /// 'Lower corner', 'Upper corner' (above the lower one in every
        /// coordinate) and 'Subdivisions'.
        void
        parse_parameters(ParameterHandler &prm) override
        {
          prm_subdivisions = prm.get("Subdivisions");
          lower_corner     = parse_point<dim>(prm.get("Lower corner"));
          upper_corner     = parse_point<dim>(prm.get("Upper corner"));
          subdivisions.clear();
          for (const int n : Utilities::string_to_int(
                 Utilities::split_string_list(prm.get("Subdivisions"))))
            subdivisions.push_back(n);
          for (unsigned int d = 0; d < dim; ++d)
            AssertThrow(upper_corner[d] > lower_corner[d],
                        ExcInvalidInput("Geometry/Upper corner",
                                        prm.get("Upper corner"),
                                        "every coordinate of the upper "
                                        "corner must exceed that of the "
                                        "lower corner (" +
                                          prm.get("Lower corner") + ")"));
        }

        void
        create_coarse_mesh(Triangulation<dim> &triangulation) const override
        {
          GridGenerator::subdivided_hyper_rectangle(
            triangulation, subdivisions, lower_corner, upper_corner, true);
        }

        std::optional<typename MeshGenerator<dim>::CoarseSize>
        coarse_size() const override
        {
          typename MeshGenerator<dim>::CoarseSize size;
          size.n_cells = 1;
          for (const auto n : subdivisions)
            size.n_cells *= n;
          size.spacing = (upper_corner[0] - lower_corner[0]) / subdivisions[0];
          size.entry   = "Geometry/Subdivisions";
          size.value   = prm_subdivisions;
          return size;
        }

      private:
        Point<dim>                lower_corner, upper_corner;
        std::vector<unsigned int> subdivisions;
        /// 'Subdivisions' as given, for messages.
        std::string prm_subdivisions;
      };


      /// The mesh in 'Mesh file', read with GridIn.
      template <int dim>
      class MeshFile : public MeshGenerator<dim>
      {
      public:
        /// 'Mesh file', which must name a readable file: refused before
        /// anything is built otherwise.
        void
        parse_parameters(ParameterHandler &prm) override
        {
          mesh_file = prm.get("Mesh file");
          AssertThrow(std::filesystem::is_regular_file(mesh_file) &&
                        std::ifstream(mesh_file).good(),
                      ExcInvalidInput("Geometry/Mesh file",
                                      mesh_file,
                                      "no readable file of this name; give "
                                      "the path of an existing mesh, "
                                      "relative to the working directory"));
        }

        void
        create_coarse_mesh(Triangulation<dim> &triangulation) const override
        {
          // GridIn's own messages ("(none)", "No vertices given") name
          // neither the file nor the entry; every process reads the file, so
          // every process fails alike.
          GridIn<dim> grid_in;
          grid_in.attach_triangulation(triangulation);
          std::string error;
          try
            {
              grid_in.read(mesh_file);
              if (triangulation.n_global_active_cells() == 0)
                error = "it holds no cells";
            }
          catch (const ExceptionBase &exc)
            {
              std::ostringstream info;
              exc.print_info(info);
              error = Utilities::trim(info.str());
            }
          catch (const std::exception &exc)
            {
              error = exc.what();
            }
          AssertThrow(
            error.empty(),
            ExcInvalidInput(
              "Geometry/Mesh file",
              mesh_file,
              "reading it as a " + std::to_string(dim) + "D mesh failed (" +
                (error.empty() ? "" : error) +
                "); check that the extension names its format (.msh, .vtk, "
                ".inp, .ucd, ...), that the file is complete, and that it "
                "holds " +
                std::to_string(dim) +
                "D cells ('Dimension = " + std::to_string(dim) + "')"));
        }

        std::vector<IO::OutputName>
        input_names() const override
        {
          return {{"Geometry/Mesh file",
                   mesh_file,
                   mesh_file,
                   IO::OutputName::Kind::input,
                   "the mesh"}};
        }

      private:
        std::string mesh_file;
      };
    } // namespace


    template class MeshGenerator<1>;
    template class MeshGenerator<2>;
    template class MeshGenerator<3>;
    template std::string
    mesh_generator_pattern<1>(const std::string &);
    template std::string
    mesh_generator_pattern<2>(const std::string &);
    template std::string
    mesh_generator_pattern<3>(const std::string &);
  } // namespace Problems

  template class PluginRegistry<Problems::MeshGenerator<1>>;
  template class PluginRegistry<Problems::MeshGenerator<2>>;
  template class PluginRegistry<Problems::MeshGenerator<3>>;
} // namespace PeriDEAL

PERIDEAL_REGISTER_MESH_GENERATOR(
  PeriDEAL::Problems::SubdividedBox,
  "subdivided box",
  "The box between 'Lower corner' and 'Upper corner' with 'Subdivisions' "
  "cells per direction (boundary ids 0/1 on x = min/max, 2/3 on y, 4/5 on "
  "z).")
PERIDEAL_REGISTER_MESH_GENERATOR(
  PeriDEAL::Problems::MeshFile,
  "file",
  "The mesh in 'Mesh file', read with deal.II's GridIn; every cell must be "
  "an axis-aligned box.")
