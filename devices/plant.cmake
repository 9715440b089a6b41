# Floor 3 plant models: the MC6000 speed loop and load (Eigen, discretised at construction).
add_library(ibs_plant ${CMAKE_CURRENT_SOURCE_DIR}/src/drive_plant.cpp)
target_include_directories(ibs_plant PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
# Eigen3::Eigen is an imported target: its headers reach every consumer as -isystem, so Eigen's
# own warnings do not count against -Werror.
target_link_libraries(ibs_plant PUBLIC Eigen3::Eigen ibs::interbus_core)
target_compile_features(ibs_plant PUBLIC cxx_std_20)
ibs_set_warnings(ibs_plant)
add_library(ibs::plant ALIAS ibs_plant)
