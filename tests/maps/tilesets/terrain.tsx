<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" tiledversion="1.10.2" name="terrain" class="Ground" tilewidth="16" tileheight="16" spacing="0" margin="0" tilecount="8" columns="4" objectalignment="bottomleft">
 <tileoffset x="2" y="-3"/>
 <properties>
  <property name="material" value="grass"/>
 </properties>
 <image source="../images/terrain.png" width="64" height="32"/>
 <tile id="0" type="Solid" probability="0.5">
  <properties>
   <property name="friction" type="float" value="0.8"/>
   <property name="slippery" type="bool" value="false"/>
  </properties>
 </tile>
 <tile id="1">
  <animation>
   <frame tileid="1" duration="100"/>
   <frame tileid="2" duration="150"/>
   <frame tileid="3" duration="200"/>
  </animation>
 </tile>
 <tile id="2">
  <objectgroup draworder="index" id="2">
   <object id="1" x="0" y="8" width="16" height="8"/>
   <object id="2" x="0" y="0">
    <polygon points="0,0 16,0 8,8"/>
   </object>
  </objectgroup>
 </tile>
</tileset>
