# Haar-wavelet sources of prt::prt (all-frequency relighting, Ng, Ramamoorthi & Hanrahan 2003).
target_sources(prt_runtime PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_cube_map.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_cube_resample.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_transform.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_approximation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_transfer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_relighter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/haar_transfer_file.cpp
)
