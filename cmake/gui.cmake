# aggpack-gui: GLFW + OpenGL 3.3 core + Dear ImGui (Debian's libimgui-dev, whose static library
# carries the GLFW and OpenGL3 backends). Optional: needs aggpack_render and aggpack_io.
# Needs (Debian): libglfw3-dev libimgui-dev (+ the render packages). Smoke test: xvfb xauth.

option(AGGPACK_BUILD_GUI "Build the interactive program aggpack-gui" ON)

if(AGGPACK_BUILD_GUI)
  find_package(glfw3 QUIET)
  find_package(Threads REQUIRED)
  if(PkgConfig_FOUND)
    pkg_check_modules(IMGUI QUIET IMPORTED_TARGET imgui)
  endif()
  if(NOT TARGET aggpack_render OR NOT TARGET aggpack_io OR NOT TARGET glfw
     OR NOT TARGET PkgConfig::IMGUI)
    message(STATUS "aggpack: aggpack-gui disabled (needs rendering, the io library, GLFW and "
                   "Dear ImGui: apt-get install libglfw3-dev libimgui-dev)")
    set(AGGPACK_BUILD_GUI OFF)
  endif()
endif()

if(AGGPACK_BUILD_GUI)
  file(GLOB AGGPACK_GUI_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/app/gui/*.cpp)
  add_executable(aggpack-gui ${AGGPACK_GUI_SOURCES})
  target_link_libraries(aggpack-gui PRIVATE aggpack_render aggpack_pipeline aggpack_config aggpack_io
                        aggpack_core
                        PkgConfig::IMGUI glfw OpenGL::OpenGL CLI11::CLI11 fmt::fmt
                        Threads::Threads ${CMAKE_DL_LIBS})

  # GUI smoke test: pack under a virtual X server, save a screenshot, inspect it.
  find_program(AGGPACK_XVFB_RUN xvfb-run)
  find_package(Python3 QUIET COMPONENTS Interpreter)
  if(AGGPACK_BUILD_TESTS AND AGGPACK_XVFB_RUN AND Python3_Interpreter_FOUND)
    enable_testing()
    add_test(NAME gui_smoke
             COMMAND ${PROJECT_SOURCE_DIR}/tests/gui/smoke_test.sh $<TARGET_FILE:aggpack-gui>
                     ${CMAKE_CURRENT_BINARY_DIR}/gui_smoke $<TARGET_FILE:aggpack>)
    set_tests_properties(gui_smoke PROPERTIES TIMEOUT 300 COST 55)
    # Open refuses every bad native file of tests/io/fixtures/bad-inputs.
    add_test(NAME gui_bad_open
             COMMAND ${PROJECT_SOURCE_DIR}/tests/gui/bad_open_test.sh $<TARGET_FILE:aggpack-gui>
                     ${CMAKE_CURRENT_BINARY_DIR}/gui_bad_open)
    set_tests_properties(gui_bad_open PROPERTIES TIMEOUT 300)
    # Screenshot tests of the layout, the out-of-date result and a field's error (issue 18).
    add_test(NAME gui_ui
             COMMAND ${PROJECT_SOURCE_DIR}/tests/gui/ui_test.sh $<TARGET_FILE:aggpack-gui>
                     ${CMAKE_CURRENT_BINARY_DIR}/gui_ui)
    set_tests_properties(gui_ui PROPERTIES TIMEOUT 300 COST 60)
    # The shape library dialog (particle.library): folder, picked files, Cancel, Chinese.
    add_test(NAME gui_library
             COMMAND ${PROJECT_SOURCE_DIR}/tests/gui/library_test.sh $<TARGET_FILE:aggpack-gui>
                     ${CMAKE_CURRENT_BINARY_DIR}/gui_library)
    set_tests_properties(gui_library PROPERTIES TIMEOUT 300)
    # The window stays live while 200,000 particles are packed and shown (a bound for CI noise;
    # the measured figure is in bench/RESULTS.md).
    add_test(NAME gui_frame_time
             COMMAND ${PROJECT_SOURCE_DIR}/tests/gui/frame_time_test.sh
                     $<TARGET_FILE:aggpack-gui> ${CMAKE_CURRENT_BINARY_DIR}/gui_frame_time)
    set_tests_properties(gui_frame_time PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)
  endif()
  # The catalogues: every text, key and word in Chinese with the English placeholders; and no
  # GUI source hands a widget English words of its own (tests/gui/check_literals.py).
  find_package(GTest QUIET)
  if(AGGPACK_BUILD_TESTS AND TARGET GTest::gtest_main)
    include(GoogleTest)
    add_executable(test_gui_i18n ${PROJECT_SOURCE_DIR}/tests/gui/i18n_test.cpp
                                 ${PROJECT_SOURCE_DIR}/tests/gui/library_words_test.cpp
                                 ${PROJECT_SOURCE_DIR}/tests/gui/library_errors_test.cpp
                                 ${PROJECT_SOURCE_DIR}/app/gui/i18n.cpp
                                 ${PROJECT_SOURCE_DIR}/app/gui/library_words.cpp
                                 ${PROJECT_SOURCE_DIR}/app/gui/system_words.cpp)
    target_include_directories(test_gui_i18n PRIVATE ${PROJECT_SOURCE_DIR}/app/gui
                                                     ${PROJECT_SOURCE_DIR}/tests)
    target_link_libraries(test_gui_i18n PRIVATE aggpack_pipeline aggpack_config aggpack_core fmt::fmt
                          aggpack_test_paths GTest::gtest_main)
    gtest_discover_tests(test_gui_i18n DISCOVERY_TIMEOUT 60)
  endif()
  if(AGGPACK_BUILD_TESTS AND Python3_Interpreter_FOUND)
    add_test(NAME gui_literals
             COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/gui/check_literals.py
                     ${PROJECT_SOURCE_DIR}/app/gui)
  endif()
endif()
