# SPDX-License-Identifier: AGPL-3.0-or-later
# cmake -DADDON_DIR= -DPACKAGE_DIR= -DSTAGE_DIR= -DZIP= -P stage_addon.cmake
# Stages dot/ (the add-on) with dot/vendor/dot_client/ (sources and stubs,
# no caches) and zips it with dot/ at the top, as Blender's installer wants.
file(REMOVE_RECURSE ${STAGE_DIR})
file(MAKE_DIRECTORY ${STAGE_DIR}/dot/vendor)
file(GLOB addon_files ${ADDON_DIR}/*.py)
file(COPY ${addon_files} DESTINATION ${STAGE_DIR}/dot)
file(WRITE ${STAGE_DIR}/dot/vendor/__init__.py
     "# dot_client and its stubs, vendored by the build (client/blender).\n")
file(GLOB_RECURSE package_files RELATIVE ${PACKAGE_DIR}
     ${PACKAGE_DIR}/*.py ${PACKAGE_DIR}/*.pyi ${PACKAGE_DIR}/py.typed)
foreach(f ${package_files})
  get_filename_component(d ${f} DIRECTORY)
  file(COPY ${PACKAGE_DIR}/${f}
       DESTINATION ${STAGE_DIR}/dot/vendor/dot_client/${d})
endforeach()
file(REMOVE ${ZIP})
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${ZIP} --format=zip dot
                WORKING_DIRECTORY ${STAGE_DIR} RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "zipping the add-on failed")
endif()
