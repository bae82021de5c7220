# mpr-view's tests (included from tools/CMakeLists.txt when SDL2 is found): scripts run with
# SDL's offscreen video driver (tests/run_script.cmake) and assertions on their screenshots
# (tests/png_compare.cpp), the saved command line reproduced by mpr-render, clean exits on Esc
# and SIGINT, one-line errors before any window opens, and real X events under Xvfb.
add_executable(mpr_view_png_compare mpr-view/tests/png_compare.cpp)
target_link_libraries(mpr_view_png_compare PRIVATE mpr::mpr)
if(TARGET mpr_warnings)
  target_link_libraries(mpr_view_png_compare PRIVATE mpr_warnings)
endif()

set(_view_tests "${CMAKE_CURRENT_SOURCE_DIR}/mpr-view/tests")
set(_view_out "${CMAKE_CURRENT_BINARY_DIR}/mpr-view-tests")
# mpr_view_test(name [SCRIPT file] [ARGS a|b] [other -D settings of run_script.cmake...])
function(mpr_view_test name)
  cmake_parse_arguments(PARSE_ARGV 1 _t "" "SCRIPT;ARGS" "")
  set(_script)
  if(_t_SCRIPT)
    set(_script "-DSCRIPT=${_view_tests}/${_t_SCRIPT}")
  endif()
  add_test(NAME mpr_view_${name}
           COMMAND "${CMAKE_COMMAND}" "-DVIEWER=$<TARGET_FILE:mpr-view>" "-DDIR=${_view_out}/${name}" ${_script}
                   "-DARGS=${_t_ARGS}" "-DCOMPARE=$<TARGET_FILE:mpr_view_png_compare>"
                   "-DREPRODUCE=$<TARGET_FILE:mpr-render>" ${_t_UNPARSED_ARGUMENTS}
                   -P "${_view_tests}/run_script.cmake")
  set_tests_properties(mpr_view_${name} PROPERTIES TIMEOUT 120)
endfunction()

mpr_view_test(help ARGS "--help" "-DEXPECT_REGEX=^usage: mpr-view.*CONTROLS.*--script FILE.*--stanford FOLDER")
# A GLC type key changes the picture and the HUD's type (mpr::glc::classify).
mpr_view_test(glc_key SCRIPT glc_key.txt ARGS "--size|320x240|--threads|2"
              "-DCHECKS=differ,a.png,g.png,picture"
              "-DEXPECT_REGEX=a.png: HUD 'default pinhole \\|.*g.png: HUD 'G cross_slit \\|")
# The wheel moves the focal plane of a light field (a rasterized virtual array of the classroom).
mpr_view_test(focus_wheel SCRIPT focus_wheel.txt ARGS "--raster|4x3|--size|320x240|--threads|2"
              "-DCHECKS=differ,near.png,far.png,picture"
              "-DEXPECT_REGEX=near.png: HUD '[^']*focus [0-9.]+ \\| synthetic.*far.png: HUD '[^']*focus [0-9.]+ \\|")
# On a real light field (Stanford Chess, when present) the wheel moves the sharp band: focused
# at the reference plane the back rows are sharper, focused nearer the front rows are.
if(EXISTS "${MPR_DATA_DIR}/stanford/chess")
  mpr_view_test(chess_focus SCRIPT chess_focus.txt ARGS "--stanford|${MPR_DATA_DIR}/stanford/chess|--size|280x160|--threads|2"
                "-DCHECKS=sharper,back.png,front.png,0:5:280:40|sharper,front.png,back.png,0:95:280:50"
                "-DEXPECT_REGEX=back.png: HUD '[^']*focus 1000 .*front.png: HUD '[^']*focus 789.4 ")
else()
  message(STATUS "mpr-view: ${MPR_DATA_DIR}/stanford/chess not found, the light-field focus test is skipped")
endif()
# Click-to-focus on a --raster array: the depth under the cursor (ray cast) becomes the focal
# depth, and the clicked board turns sharp.
mpr_view_test(click_focus SCRIPT click_focus.txt ARGS "--raster|8x6|--size|320x240|--threads|2"
              "-DCHECKS=sharper,after.png,before.png,100:70:120:50"
              "-DEXPECT_REGEX=pixel 160,60: ray from [^\n]*first hit at ray parameter 16.6.*after.png: HUD '[^']*focus 16.6")
# The help overlay covers the picture and goes away again.
mpr_view_test(help_overlay SCRIPT help.txt ARGS "--size|320x240|--threads|2"
              "-DCHECKS=differ,a.png,help.png,picture|same,a.png,back.png,picture")
# S saves the picture and the mpr-render command line that renders the same PNG.
mpr_view_test(save_scene SCRIPT save_scene.txt ARGS "--size|200x150|--threads|2|--output|found/view.png"
              -DSAVED=found/view_0001 "-DEXPECT_REGEX=saved found/view_0001.png.*mpr-render [^']*--view G")
# The cylinder key starts from mpr-render's default radius, the camera spacing (the 8 m plane
# over 4 columns: 2), and ']' widens it by 1.25.
mpr_view_test(save_raster SCRIPT save_raster.txt ARGS "--raster|4x3|--size|200x150|--threads|2"
              -DSAVED=mpr-view_0001 "-DEXPECT_REGEX=mpr-render --raster 4x3 --interp cylinder --radius 2.5 ")
# Resizing the window renders the view again at the new size: the screenshot takes the window's
# size, and the PNG that S saves is mpr-render's at that size, byte for byte.
mpr_view_test(resize SCRIPT resize.txt ARGS "--view|G|--size|200x150|--threads|2"
              "-DCHECKS=size,small.png,200x150|size,big.png,360x200" -DSAVED=mpr-view_0001
              "-DEXPECT_REGEX=saved mpr-view_0001.png[^\n]*\n[^\n]*--size 360x200")
# --spp and --aperture reach the viewer's renders: the picture differs from the pinhole's of one
# sample a pixel (a baseline run without them) and is less sharp, and mpr-render reproduces it.
mpr_view_test(spp_aperture SCRIPT spp_aperture.txt
              ARGS "--view|G|--size|200x150|--threads|2|--spp|8|--aperture|disc:0.6|--focus|9"
              "-DBASELINE_ARGS=--view|G|--size|200x150|--threads|2"
              "-DCHECKS=differ,a.png,baseline/a.png,picture|sharper,baseline/a.png,a.png,picture" -DSAVED=mpr-view_0001
              "-DEXPECT_REGEX=saved mpr-view_0001.png[^\n]*\n[^\n]*--spp 8 --filter box:0.5 --aperture disc:0.6 --focus 9")
# The HUD shows the plane's tilt (arrow keys) and a scene plane's orbit (left drag).
mpr_view_test(hud_tilt_orbit SCRIPT hud_tilt_orbit.txt ARGS "--size|320x240|--threads|2"
              "-DEXPECT_REGEX=level.png: HUD 'default pinhole \\| [0-9.]+ ms'.*moved.png: HUD '[^']*\\| tilt 2,-2 \\| orbit -12,0'")
# Esc closes the window before the script ends; so does SIGINT.
mpr_view_test(escape SCRIPT escape.txt ARGS "--size|64x48" -DNO_FILE=never.png)
if(UNIX)
  mpr_view_test(sigint SCRIPT sigint.txt ARGS "--size|64x48" -DSIGINT_AFTER=3 -DNO_FILE=never.png)
endif()
# Bad input: one line, exit 1, before any window opens (a video driver that does not exist
# would fail SDL_Init with another message).
mpr_view_test(bad_input ARGS "--stanford|/nonexistent/folder" -DDRIVER=no_such_driver -DEXPECT_RC=1
              "-DEXPECT_REGEX=^mpr-view: /nonexistent/folder: no such folder\n$")
mpr_view_test(bad_option ARGS "--size|0x10" -DDRIVER=no_such_driver -DEXPECT_RC=1
              "-DEXPECT_REGEX=^mpr-view: invalid --size: 0 is outside")
mpr_view_test(bad_script_command SCRIPT bad_command.txt -DDRIVER=no_such_driver -DEXPECT_RC=1
              "-DEXPECT_REGEX=^mpr-view: [^\n]*bad_command.txt:2: unknown command 'kye'")
mpr_view_test(bad_script_key SCRIPT bad_key.txt -DDRIVER=no_such_driver -DEXPECT_RC=1
              "-DEXPECT_REGEX=^mpr-view: [^\n]*bad_key.txt:1: 'NoSuchKey' is not an SDL key name")
# --benchmark-frames belongs to --benchmark: alone it is refused, naming both options.
mpr_view_test(benchmark_frames_alone ARGS "--benchmark-frames|3|--size|64x48" -DDRIVER=no_such_driver -DEXPECT_RC=1
              "-DEXPECT_REGEX=^mpr-view: invalid --benchmark-frames: needs --benchmark[^\n]*\n$")
# The benchmark mode runs (numbers belong in docs/mpr-view.md, not here).
mpr_view_test(benchmark_smoke ARGS "--benchmark|--benchmark-frames|2|--size|64x48|--threads|2"
              "-DEXPECT_REGEX=full resolution: +median [0-9.]+ ms = [0-9.]+ frames/s.*input event -> first frame")

# Real X events: xdotool types into the window under Xvfb.
find_program(MPR_XVFB_RUN xvfb-run)
find_program(MPR_XDOTOOL xdotool)
if(MPR_XVFB_RUN AND MPR_XDOTOOL)
  add_test(NAME mpr_view_xvfb_xdotool
           COMMAND "${MPR_XVFB_RUN}" -a "${CMAKE_COMMAND}" "-DVIEWER=$<TARGET_FILE:mpr-view>"
                   "-DCOMPARE=$<TARGET_FILE:mpr_view_png_compare>" "-DXDOTOOL=${MPR_XDOTOOL}"
                   "-DDIR=${_view_out}/xvfb" -P "${_view_tests}/xdotool.cmake")
  set_tests_properties(mpr_view_xvfb_xdotool PROPERTIES TIMEOUT 120)
else()
  message(STATUS "mpr-view: xvfb-run or xdotool not found, the test with real X events is skipped")
endif()
# --script limits (issue 48): a line over 1024 bytes and a file over 1 MiB, one line each.
mpr_view_test(bad_script_long_line SCRIPT long_line.txt -DDRIVER=no_such_driver -DEXPECT_RC=1
              "-DEXPECT_REGEX=^mpr-view: [^\n]*long_line.txt:2: line longer than 1024 bytes\n$")
string(REPEAT "wait 1\n" 160000 _big_script)
file(WRITE "${_view_out}/big_script.txt" "${_big_script}")
mpr_view_test(bad_script_size -DDRIVER=no_such_driver -DEXPECT_RC=1 "-DSCRIPT=${_view_out}/big_script.txt"
              "-DEXPECT_REGEX=^mpr-view: [^\n]*big_script.txt: 1120000 bytes: scripts are limited to 1048576 bytes\n$")
