<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" tiledversion="1.10.2" name="tiles" tilewidth="16" tileheight="16" tilecount="8" columns="8">
 <image source="../assets/tiles.png" width="128" height="16"/>
 <tile id="0" type="ground"/>
 <tile id="1" type="brick"/>
 <tile id="2" type="grass"/>
 <tile id="3" type="platform">
  <properties>
   <property name="one-way" type="bool" value="true"/>
  </properties>
 </tile>
 <tile id="4" type="spikes"/>
 <tile id="5" type="coin"/>
 <tile id="6" type="background"/>
 <tile id="7" type="stone"/>
</tileset>
