# Floor 1 bus layer: ID codes, bus configuration, process image, cycle-time formula.
add_library(ibs_interbus_bus
  ${CMAKE_CURRENT_SOURCE_DIR}/src/id_code.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/bus_config.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/process_image.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/cycle_time.cpp)
ibs_export(ibs_interbus_bus interbus_bus HEADERS ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(ibs_interbus_bus PUBLIC ibs::interbus_core)
target_compile_features(ibs_interbus_bus PUBLIC cxx_std_20)
ibs_set_warnings(ibs_interbus_bus)
add_library(ibs::interbus_bus ALIAS ibs_interbus_bus)
