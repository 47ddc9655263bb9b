# SPDX-License-Identifier: AGPL-3.0-or-later
# dot_man_page(TARGET "SUMMARY"): a man page for an executable target made
# by help2man from its own --help and --version (so it cannot drift from
# the flags), built with the target and installed in man1. Skipped, with a
# note, where help2man is not installed (Debian: help2man).
include(GNUInstallDirs)
find_program(HELP2MAN help2man)
function(dot_man_page target summary)
  if(NOT HELP2MAN)
    message(STATUS "help2man not found: no man page for ${target}")
    return()
  endif()
  set(page ${CMAKE_CURRENT_BINARY_DIR}/${target}.1)
  add_custom_command(OUTPUT ${page}
    COMMAND ${HELP2MAN} --no-info --no-discard-stderr --name=${summary}
            --output=${page} $<TARGET_FILE:${target}>
    DEPENDS ${target}
    COMMENT "man page of ${target} (help2man)")
  add_custom_target(${target}_man ALL DEPENDS ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endfunction()
