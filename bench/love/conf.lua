-- LÖVE 11.4 side of bench/draw.scm (docs/performance.org, "Drawing
-- against LÖVE"): an 800 x 600 window without vsync, no audio.
function love.conf(t)
  t.window.width = 800
  t.window.height = 600
  t.window.vsync = 0
  t.window.title = "draw bench (LOVE)"
  t.modules.audio = false
  t.modules.sound = false
  t.modules.joystick = false
  t.modules.physics = false
end
