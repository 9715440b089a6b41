# Scenario files for `ibs run` (docs/scenarios.md): the data model, TOML and JSON readers and
# writers, and the validator. toml++ and nlohmann-json are Debian packages; their imported
# targets make their headers SYSTEM includes, outside the project's warnings.
find_package(tomlplusplus 3 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)

add_library(ibs_scenario
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario_text.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario_schema.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario_validate.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario_write.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario_toml.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scenario_json.cpp)
ibs_export(ibs_scenario scenario HEADERS ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(ibs_scenario
  PUBLIC ibs::devices_api ibs::interbus_core ibs::interbus_bus
  PRIVATE ibs::devices tomlplusplus::tomlplusplus nlohmann_json::nlohmann_json)
target_compile_features(ibs_scenario PUBLIC cxx_std_20)
ibs_set_warnings(ibs_scenario)
add_library(ibs::scenario ALIAS ibs_scenario)
