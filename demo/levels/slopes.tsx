<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" tiledversion="1.10.2" name="slopes" tilewidth="16" tileheight="16" tilecount="3" columns="3">
 <image source="../assets/slopes.png" width="48" height="16"/>
 <tile id="0" type="slope">
  <properties>
   <property name="slope-left" type="int" value="0"/>
   <property name="slope-right" type="int" value="16"/>
  </properties>
 </tile>
 <tile id="1" type="slope">
  <properties>
   <property name="slope-left" type="int" value="0"/>
   <property name="slope-right" type="int" value="8"/>
  </properties>
 </tile>
 <tile id="2" type="slope">
  <objectgroup draworder="index" id="2">
   <object id="1" x="0" y="0">
    <polygon points="0,8 16,0 16,16 0,16"/>
   </object>
  </objectgroup>
 </tile>
</tileset>
