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

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    MeshGenerator<dim>::create_mesh(Triangulation<dim> &triangulation,
                                    const unsigned int global_refinements) const
    {
      create_coarse_mesh(triangulation);
      triangulation.refine_global(global_refinements);
    }


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
          GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                    subdivisions,
                                                    lower_corner,
                                                    upper_corner,
                                                    true);
        }

        /**
         * The same cells, faster: a p4est forest of n coarse cells per
         * direction costs about 40 s at n = 100 in 3D (one tree per cell:
         * the connectivity, its hierarchical reordering and a deal.II
         * coarse cell each), while refining is about 5 s per 10^6 cells.
         * So the box is built with 'Subdivisions' / 2^r cells per direction
         * (r the largest with 2^r dividing every entry) and refined
         * r + @p global_refinements times. Refinement places the vertices
         * at midpoints, which differ from the uniform lattice in round-off;
         * they are then snapped to it, x = lower + i (upper - lower) / n
         * with n the fine number of cells, which is exactly where
         * subdivided_hyper_rectangle() puts them: with 'Global refinements
         * = 0' the nodes are where create_coarse_mesh() alone puts them, to
         * the bit (tests/discretization/mesh_generator_box). Only the order of
         * the cells, and so of the nodes and the partition, changes. With
         * global refinements the nodes lie on the exact lattice too (the
         * default path leaves them at the round-off of the midpoints).
         */
        void
        create_mesh(Triangulation<dim> &triangulation,
                    const unsigned int  global_refinements) const override
        {
          // (At most 10: p4est's deepest level is far below, and any box
          // with fewer coarse cells than 2^10 per direction builds fast.)
          unsigned int r = 0;
          while (r < 10 && std::all_of(subdivisions.begin(),
                                       subdivisions.end(),
                                       [r](const unsigned int n) {
                                         return n % (2u << r) == 0;
                                       }))
            ++r;
          std::vector<unsigned int> coarse(subdivisions);
          for (auto &n : coarse)
            n >>= r;
          GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                    coarse,
                                                    lower_corner,
                                                    upper_corner,
                                                    true);
          triangulation.refine_global(r + global_refinements);

          // The fine lattice spacing, computed as subdivided_hyper_rectangle
          // computes its own (the side over the number of cells).
          Point<dim> spacing;
          for (unsigned int d = 0; d < dim; ++d)
            spacing[d] = (upper_corner[d] - lower_corner[d]) /
                         (subdivisions[d] << global_refinements);
          // Every vertex of every active cell (owned, ghost or artificial;
          // a parent's vertices are its children's), independently of the
          // others: unlike GridTools::transform(), which moves the hanging
          // vertices of a distributed mesh's ghost layer to their faces'
          // means, so that a ghost node could differ from its owner's.
          for (const auto &cell : triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              {
                Point<dim> &x = cell->vertex(v);
                for (unsigned int d = 0; d < dim; ++d)
                  x[d] = lower_corner[d] +
                         std::round((x[d] - lower_corner[d]) / spacing[d]) *
                           spacing[d];
              }
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
