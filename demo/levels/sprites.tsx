<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" tiledversion="1.10.2" name="sprites" tilewidth="16" tileheight="16" tilecount="18" columns="6">
 <image source="../assets/sprites.png" width="96" height="48"/>
</tileset>
