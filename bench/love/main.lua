-- The same work as bench/draw.scm, in LÖVE 11.4:
--   xvfb-run -a -s "-screen 0 1024x768x24" love bench/love SCENE [N]
-- SCENE: sprites (N 16 x 16 sprites of one 64 x 16 sheet, kept in a table
-- and each moved every frame by an update), fancy (the same turned, scaled
-- 1.5 and at alpha 160), map (a 200 x 200 three-layer map of 16 x 16
-- tiles scrolling (3, 2) px a frame, each layer one SpriteBatch built once,
-- as the Simple Tiled Implementation library draws Tiled maps). Prints the
-- CPU time (os.clock: user + system, all threads) per frame of FRAMES
-- frames (default 300) after 30 of warm-up, and the places drawn (as
-- bench/draw.scm prints them; tools/bench-draw.sh checks they match).

local scene, n, frames, warmup = "sprites", 1000, tonumber(os.getenv("FRAMES") or "300"), 30
local W, H = 800, 600

-- bench/draw.scm's integer generator, exactly: a Lua number is a double,
-- and 1103515245 * seed (up to 2^61) would lose its low bits (which put
-- every sprite on a multiple of 8 px, cheaper for the rasterizer than
-- Downstroke's places), so the product is taken in two halves of seed.
local seed = 20261121
local function draw()
  local hi, lo = math.floor(seed / 65536), seed % 65536
  seed = ((1103515245 * hi) % 32768 * 65536 + 1103515245 * lo + 12345) % 2147483648
  return seed
end

-- What both sides print after the time, to show they drew the same:
-- sprites, the sums of their first places; the map, its cells and the
-- sum of their tile numbers.
local places = ""

-- A sheet of columns x rows 16 x 16 tiles, as bench/draw.scm makes it.
local function sheet(columns, rows)
  local data = love.image.newImageData(16 * columns, 16 * rows)
  for i = 0, columns * rows - 1 do
    local x0, y0 = 16 * (i % columns), 16 * math.floor(i / columns)
    local r, g, b = (60 * i) % 256, 200, (255 - 37 * i) % 256
    for y = 0, 15 do
      for x = 0, 15 do
        if x == 0 or y == 0 or x == 15 or y == 15 then
          data:setPixel(x0 + x, y0 + y, 0, 0, 0, 1)
        else
          data:setPixel(x0 + x, y0 + y, r / 255, g / 255, b / 255, 1)
        end
      end
    end
  end
  local img = love.graphics.newImage(data)
  img:setFilter("nearest", "nearest")
  local quads = {}
  for i = 0, columns * rows - 1 do
    quads[i + 1] = love.graphics.newQuad(16 * (i % columns), 16 * math.floor(i / columns), 16, 16,
                                         img:getDimensions())
  end
  return img, quads
end

local frame_fn

-- The sprites are kept, as a game keeps them, and moved by an update each
-- frame (x += dx, wrapping; fancy: angle += 2), as bench/draw.scm's
-- entities are: the same places and angles as (x0 + f dx) mod (W - 16).
local function sprites(fancy)
  local img, quads = sheet(4, 1)
  local list = {}
  for i = 0, n - 1 do
    local x = draw() % (W - 16)
    local y = draw() % (H - 16)
    list[i + 1] = { x = x, y = y, dx = 1 + i % 3, quad = quads[1 + i % 4], angle = (2 * i) % 360 }
  end
  local sx, sy = 0, 0
  for _, s in ipairs(list) do sx, sy = sx + s.x, sy + s.y end
  places = string.format("%d/%d", sx, sy)
  return function(f)
    if f > 0 then
      for _, s in ipairs(list) do
        s.x = (s.x + s.dx) % (W - 16)
        if fancy then s.angle = (s.angle + 2) % 360 end
      end
    end
    love.graphics.clear(0, 0, 0)
    if fancy then love.graphics.setColor(1, 1, 1, 160 / 255) end
    for _, s in ipairs(list) do
      if fancy then
        -- scaled 1.5 and turned about the sprite's centre, as #:scale and #:angle do
        love.graphics.draw(img, s.quad, s.x + 8, s.y + 8, math.rad(s.angle), 1.5, 1.5, 8, 8)
      else
        love.graphics.draw(img, s.quad, s.x, s.y)
      end
    end
    love.graphics.setColor(1, 1, 1, 1)
  end
end

local function tilemap()
  local img, quads = sheet(4, 4)
  local batches, cells, sum = {}, 0, 0
  for k, percent in ipairs({100, 33, 10}) do
    local b = love.graphics.newSpriteBatch(img, 200 * 200, "static")
    for i = 0, 200 * 200 - 1 do
      if draw() % 100 < percent then
        local tile = 1 + draw() % 16
        b:add(quads[tile], 16 * (i % 200), 16 * math.floor(i / 200))
        cells, sum = cells + 1, sum + tile
      end
    end
    batches[k] = b
  end
  places = string.format("%d/%d", cells, sum)
  local max_x, max_y = 200 * 16 - W, 200 * 16 - H
  return function(f)
    love.graphics.clear(0, 0, 0)
    love.graphics.push()
    love.graphics.translate(-((3 * f) % max_x), -((2 * f) % max_y))
    for _, b in ipairs(batches) do love.graphics.draw(b) end
    love.graphics.pop()
  end
end

function love.load(args)
  scene = args[1] or scene
  n = tonumber(args[2] or "") or n
  if scene == "sprites" then frame_fn = sprites(false)
  elseif scene == "fancy" then frame_fn = sprites(true)
  elseif scene == "map" then frame_fn = tilemap()
  else error("unknown scene (sprites, fancy, map): " .. tostring(scene)) end
end

function love.run()
  love.load(love.arg.parseGameArguments(arg))
  local t0, w0
  for f = 0, warmup + frames - 1 do
    if f == warmup then t0, w0 = os.clock(), love.timer.getTime() end
    love.event.pump()
    for name in love.event.poll() do if name == "quit" then return 0 end end
    frame_fn(f)
    love.graphics.present()
  end
  local cpu, wall = os.clock() - t0, love.timer.getTime() - w0
  print(string.format("love %s %s (%s): %.3f ms CPU per frame, %.3f ms wall, places %s",
                      scene, scene == "map" and "200x200x3" or tostring(n),
                      (select(1, love.graphics.getRendererInfo())),
                      1000 * cpu / frames, 1000 * wall / frames, places))
  return function() return 0 end
end
