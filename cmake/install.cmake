# What `cmake --install` puts in place (docs/embedding.md): headers, the libraries of the master
# (ibs::master) and, unless IBS_MASTER_ONLY, of the simulator and emulators (ibs::sim), the `ibs`
# tool, a CMake package (find_package(ibs)) and a pkg-config file for the master (ibs-master).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# ibs_export(target EXPORT_NAME [INTERFACE] HEADERS dir...): `target` goes into the package as
# ibs::EXPORT_NAME, with `dir`s as its include directories in the build tree and the installed
# include directory afterwards; the headers under each dir are installed.
function(ibs_export target export_name)
  cmake_parse_arguments(arg "INTERFACE" "" "HEADERS" ${ARGN})
  set(scope PUBLIC)
  if(arg_INTERFACE)
    set(scope INTERFACE)
  endif()
  foreach(dir IN LISTS arg_HEADERS)
    target_include_directories(${target} ${scope} $<BUILD_INTERFACE:${dir}>)
    set_property(GLOBAL APPEND PROPERTY IBS_HEADER_DIRS ${dir})
  endforeach()
  target_include_directories(${target} ${scope} $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  set_property(GLOBAL APPEND PROPERTY IBS_EXPORTED_TARGETS ${target})
endfunction()

# ibs_replay_only(target SOURCES file... HEADERS name...): sources that serve tests, replay and the
# command line (traces and their adapters), never the cycle path. The default build compiles them
# into `target`; the embedded build (IBS_EMBEDDED, docs/embedding.md) leaves them out and does not
# install the headers of those names.
function(ibs_replay_only target)
  cmake_parse_arguments(arg "" "" "SOURCES;HEADERS" ${ARGN})
  if(IBS_EMBEDDED)
    set_property(GLOBAL APPEND PROPERTY IBS_EXCLUDED_HEADERS ${arg_HEADERS})
  else()
    target_sources(${target} PRIVATE ${arg_SOURCES})
  endif()
endfunction()

# Called once at the end of the top-level CMakeLists.txt, when every target exists.
function(ibs_install)
  get_property(targets GLOBAL PROPERTY IBS_EXPORTED_TARGETS)
  get_property(header_dirs GLOBAL PROPERTY IBS_HEADER_DIRS)
  # Several targets share a header folder (base/include by many): install each folder once.
  list(REMOVE_DUPLICATES header_dirs)
  # Building the tool builds everything installed, so that `cmake --build --target ibs` followed
  # by `cmake --install` (the docs' way, docs/embedding.md) finds every library it installs, also
  # those the tool does not link (od's text readers, the dictionaries' users).
  if(TARGET ibs)
    foreach(t IN LISTS targets)
      get_target_property(type ${t} TYPE)
      if(NOT type STREQUAL "INTERFACE_LIBRARY")
        add_dependencies(ibs ${t})
      endif()
    endforeach()
  endif()
  install(TARGETS ${targets} EXPORT ibs-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # Headers of the sources a build leaves out (IBS_EMBEDDED: the trace and replay code).
  get_property(excluded GLOBAL PROPERTY IBS_EXCLUDED_HEADERS)
  set(exclude_patterns "")
  foreach(name IN LISTS excluded)
    list(APPEND exclude_patterns PATTERN ${name} EXCLUDE)
  endforeach()
  foreach(dir IN LISTS header_dirs)
    install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp"
            ${exclude_patterns})
  endforeach()
  set(cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/ibs)
  install(EXPORT ibs-targets NAMESPACE ibs:: DESTINATION ${cmake_dir})
  # The package's dependencies: none for the master; the simulator's when it was built.
  set(IBS_PACKAGE_HAS_SIM OFF)
  if(NOT IBS_MASTER_ONLY)
    set(IBS_PACKAGE_HAS_SIM ON)
  endif()
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ibs-config.cmake.in
                                ${PROJECT_BINARY_DIR}/ibs-config.cmake INSTALL_DESTINATION ${cmake_dir})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/ibs-config-version.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/ibs-config.cmake ${PROJECT_BINARY_DIR}/ibs-config-version.cmake
          DESTINATION ${cmake_dir})
  # pkg-config: the master's libraries in link order (each after the ones that need it).
  set(IBS_MASTER_PKG_LIBS "")
  set(libs ibs_master ibs_vf1000_master ibs_mc6000_master ibs_devices_api ibs_vf1000_channel
           ibs_vf1000_table ibs_mc6000_core ibs_pcp ibs_drive ibs_od ibs_drivecom ibs_interbus_bus)
  if(NOT IBS_EMBEDDED)
    list(APPEND libs ibs_interbus_core)  # traces and replay: headers only in the embedded build
  endif()
  foreach(lib ${libs} ibs_base)
    string(APPEND IBS_MASTER_PKG_LIBS " -l${lib}")
  endforeach()
  # The prefix relative to the .pc file, so that `cmake --install --prefix DIR` works too.
  file(RELATIVE_PATH IBS_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/ibs-master.pc.in ${PROJECT_BINARY_DIR}/ibs-master.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/ibs-master.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
  if(NOT IBS_MASTER_ONLY)
    # The hosts of the other buses with their transports (docs/embedding.md, "Hosts on the other
    # buses"), each library after the ones that need it, then the system's.
    ibs_host_pc(ibs-lustbus "ibs LUSTBUS host (seed 000) with serial ports and pseudo-terminals"
                "ibs_lustbus_serial ibs_serial_capture ibs_lustbus ibs_serial ibs_pcap ibs_drive ibs_od ibs_base"
                "-lutil -pthread -lpcap")
    ibs_host_pc(ibs-canlust "ibs CANLust master side (seed 003) with CAN over UDP and SocketCAN"
                "ibs_can_transport ibs_canlust ibs_base" "-lpcap")
    ibs_host_pc(ibs-dfs1 "ibs PowerTec DFS-1 host (seed 004) with serial ports and pseudo-terminals"
                "ibs_dfs1_serial ibs_serial_capture ibs_dfs1 ibs_serial ibs_pcap ibs_base" "-lutil -pthread -lpcap")
    # The cycle simulator and the drives' emulators (ibs::sim), in the link order CMake derives for
    # ibs::sim (tools/check_install.sh links a program through this file and runs it).
    set(sim_requires "eigen3 tomlplusplus")
    if(IBS_PCAP_INCLUDE_DIR AND IBS_PCAP_LIBRARY)
      string(APPEND sim_requires " libpcap")
    endif()
    ibs_host_pc(ibs-sim "ibs cycle simulator and the drives' emulators (INTERBUS, with captures and VCD)"
                "ibs_sim ibs_master ibs_scenario ibs_devices ibs_vf1000_device ibs_vf1000_master ibs_vf1000_channel
                 ibs_vf1000_core ibs_vf1000_table ibs_mc6000_device ibs_plant ibs_mc6000_master ibs_mc6000_core ibs_pcp
                 ibs_drive ibs_od ibs_devices_api ibs_drivecom ibs_interbus_bus ibs_vcd ibs_interbus_core ibs_pcap ibs_base"
                "-pthread" REQUIRES "${sim_requires}")
    # The Wireshark dissectors, laid out as a Wireshark plugin folder (docs/pcap.md, "Installed").
    install(FILES ${PROJECT_SOURCE_DIR}/tools/wireshark/interbus.lua ${PROJECT_SOURCE_DIR}/tools/wireshark/canlust.lua
                  ${PROJECT_SOURCE_DIR}/tools/wireshark/lustbus.lua ${PROJECT_SOURCE_DIR}/tools/wireshark/dfs1.lua
            DESTINATION ${CMAKE_INSTALL_DATADIR}/ibs/wireshark/plugins)
  endif()
endfunction()

# ibs_host_pc(NAME DESCRIPTION "LIB..." "SYSTEM-FLAGS" [REQUIRES "PKG..."]): NAME.pc for a bus
# host's libraries; REQUIRES names the pkg-config packages they need.
function(ibs_host_pc name description libs system)
  cmake_parse_arguments(arg "" "REQUIRES" "" ${ARGN})
  set(IBS_PC_REQUIRES "")
  if(arg_REQUIRES)
    set(IBS_PC_REQUIRES "Requires: ${arg_REQUIRES}")
  endif()
  set(IBS_PC_NAME ${name})
  set(IBS_PC_DESCRIPTION ${description})
  set(IBS_PC_LIBS "")
  string(REGEX REPLACE "[ \t\n]+" " " libs "${libs}")
  string(STRIP "${libs}" libs)
  separate_arguments(libs)
  foreach(lib IN LISTS libs)
    string(APPEND IBS_PC_LIBS " -l${lib}")
  endforeach()
  string(APPEND IBS_PC_LIBS " ${system}")
  file(RELATIVE_PATH IBS_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/ibs-host.pc.in ${PROJECT_BINARY_DIR}/${name}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${name}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
