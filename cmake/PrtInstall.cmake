# prt_install_component(TARGET name COMPONENT component [HEADERS dir])
# Installs a library as the exported component prt::<component>: its archive, its public headers
# (the folder `dir`, default <folder>/include/; a folder given without a trailing slash is installed
# as a folder of that name), and prt_<component>Targets.cmake, which
# cmake/prtConfig.cmake.in includes when the component is asked for.
include(GNUInstallDirs)
function(prt_install_component)
  cmake_parse_arguments(C "" "TARGET;COMPONENT;HEADERS" "" ${ARGN})
  if(NOT C_HEADERS)
    set(C_HEADERS ${CMAKE_CURRENT_SOURCE_DIR}/include/)
  endif()
  set_target_properties(${C_TARGET} PROPERTIES EXPORT_NAME ${C_COMPONENT})
  install(TARGETS ${C_TARGET} EXPORT prt_${C_COMPONENT}Targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${C_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT prt_${C_COMPONENT}Targets NAMESPACE prt::
          FILE prt_${C_COMPONENT}Targets.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/prt)
endfunction()
