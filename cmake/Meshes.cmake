# SPDX-License-Identifier: AGPL-3.0-or-later
# Real meshes for the hole tests and benchmarks, extracted at build time from
# Debian's libcgal-demo (never committed). Defines DOT_MESH_DIR and, when the
# archive is installed, the target dot_meshes.
set(DOT_MESH_DIR ${PROJECT_BINARY_DIR}/data/meshes)
set(CGAL_DATA_TARBALL /usr/share/doc/libcgal-dev/data.tar.gz)
set(DOT_MESHES elephant.off armadillo.off refined_elephant.off bunny00.off
    elephant-with-holes.off holes.off lion.off mech-holes-shark.off head.off
    homer.off)
list(TRANSFORM DOT_MESHES PREPEND ${DOT_MESH_DIR}/ OUTPUT_VARIABLE DOT_MESH_FILES)
list(TRANSFORM DOT_MESHES PREPEND data/meshes/ OUTPUT_VARIABLE DOT_MESH_MEMBERS)
if(EXISTS ${CGAL_DATA_TARBALL})
  add_custom_command(OUTPUT ${DOT_MESH_FILES}
    COMMAND ${CMAKE_COMMAND} -E tar xzf ${CGAL_DATA_TARBALL} ${DOT_MESH_MEMBERS}
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    DEPENDS ${CGAL_DATA_TARBALL}
    COMMENT "Extracting meshes from libcgal-demo")
  add_custom_target(dot_meshes DEPENDS ${DOT_MESH_FILES})
endif()
