<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" tiledversion="1.10.2" name="ladders" tilewidth="16" tileheight="16" tilecount="1" columns="1">
 <image source="../assets/ladder.png" width="16" height="16"/>
 <tile id="0" type="ladder">
  <properties>
   <property name="ladder" type="bool" value="true"/>
  </properties>
 </tile>
</tileset>
