# Runs under xvfb-run: mpr-view on a real X display, driven by real X events from xdotool
# (the key G, then Esc). Checks that G changed the picture and the HUD, and that Esc closed the
# window before the script reached its last screenshot.
#   cmake -DVIEWER=<mpr-view> -DCOMPARE=<png_compare> -DXDOTOOL=<xdotool> -DDIR=<folder> -P xdotool.cmake
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(WRITE "${DIR}/script.txt" "screenshot a.png\nwait 5000\nscreenshot g.png\nwait 60000\nscreenshot never.png\n")
set(ENV{SDL_VIDEODRIVER} x11)
set(ENV{ASAN_OPTIONS} "detect_leaks=0") # SDL's own leak at exit (see run_script.cmake)
set(_sh [=[
"$VIEWER" --size 320x240 --threads 2 --script script.txt > viewer.log 2>&1 &
pid=$!
wid=$("$XDOTOOL" search --sync --name '^mpr-view$' | head -n 1)
"$XDOTOOL" windowfocus --sync "$wid" 2>/dev/null || "$XDOTOOL" windowfocus "$wid"
sleep 1.5
"$XDOTOOL" key --clearmodifiers g
sleep 6
"$XDOTOOL" key --clearmodifiers Escape
wait $pid
echo "viewer exit $?"
]=])
set(ENV{VIEWER} "${VIEWER}")
set(ENV{XDOTOOL} "${XDOTOOL}")
execute_process(COMMAND sh -c "${_sh}" WORKING_DIRECTORY "${DIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err TIMEOUT 100)
file(READ "${DIR}/viewer.log" log)
message("${out}${err}${log}")
if(NOT out MATCHES "viewer exit 0")
  message(FATAL_ERROR "xdotool: the viewer did not exit cleanly")
endif()
if(EXISTS "${DIR}/never.png")
  message(FATAL_ERROR "xdotool: Esc did not close the window")
endif()
if(NOT log MATCHES "g.png: HUD 'G cross_slit")
  message(FATAL_ERROR "xdotool: the key G did not reach the viewer (HUD)")
endif()
execute_process(COMMAND "${COMPARE}" differ a.png g.png picture WORKING_DIRECTORY "${DIR}" RESULT_VARIABLE crc
                OUTPUT_VARIABLE cout)
message("${cout}")
if(NOT crc EQUAL 0)
  message(FATAL_ERROR "xdotool: the key G did not change the picture")
endif()
