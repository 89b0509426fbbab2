# Third-party libraries, all from Debian 12 packages (see README.md for the apt line).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(Boost 1.74 REQUIRED COMPONENTS graph)
find_package(CGAL REQUIRED)
# VTK's data, filter and file modules serve every layer; its rendering modules only the edge
# (pipeline/render, pipeline/view), so that the core links without OpenGL or a display.
set(LIGSIM_VTK_DATA_COMPONENTS
  CommonCore CommonDataModel CommonExecutionModel
  FiltersCore FiltersGeneral FiltersGeometry FiltersSources
  IOCore IOGeometry IOLegacy IOPLY IOXML IOImage ImagingGeneral)
set(LIGSIM_VTK_RENDERING_COMPONENTS
  # Pictures: off-screen OpenGL through X, text, charts.
  RenderingCore RenderingOpenGL2 RenderingFreeType RenderingAnnotation InteractionStyle
  # The live window: the angle slider.
  InteractionWidgets
  ChartsCore ViewsContext2D RenderingContext2D RenderingContextOpenGL2)
find_package(VTK REQUIRED COMPONENTS ${LIGSIM_VTK_DATA_COMPONENTS} ${LIGSIM_VTK_RENDERING_COMPONENTS})
list(TRANSFORM LIGSIM_VTK_DATA_COMPONENTS PREPEND VTK:: OUTPUT_VARIABLE LIGSIM_VTK_DATA)
list(TRANSFORM LIGSIM_VTK_RENDERING_COMPONENTS PREPEND VTK:: OUTPUT_VARIABLE LIGSIM_VTK_RENDERING)
# Xlib, to check that an X display answers before rendering on it.
find_package(X11 REQUIRED)

# CHOLMOD (SuiteSparse) is the sparse direct solver: supernodal Cholesky is several
# times faster than Eigen's simplicial one on 3-D stiffness matrices.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
add_library(ligsim_cholmod INTERFACE)
target_include_directories(ligsim_cholmod INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(ligsim_cholmod INTERFACE ${CHOLMOD_LIBRARY})

# OpenVDB: sparse volumes and narrow-band level sets. Its find module lives beside the library
# and asks Boost for iostreams. Configuring prints a harmless warning about Debian's Imath
# Python binding, which is not installed.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

# ITK: reading and writing segmentation label maps (NRRD, NIfTI, MetaImage). Only the modules
# we use, and no ITK_USE_FILE: stages/labelmap/label_image.cpp registers its three formats.
find_package(ITK REQUIRED COMPONENTS ITKCommon ITKIOImageBase ITKIONRRD ITKIONIFTI ITKIOMeta)
