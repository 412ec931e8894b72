// Runs in the page before the game's main (make web links it with
// --pre-js). The game's save directory, SDL's per-user folder /libsdl, is
// kept in the browser's storage (IndexedDB): it is read back before the
// game starts, and written after each game-save! (shell/engine.scm).
// DISPLAY tells a game that reads it, as the demos do, that it has a screen.
Module.preRun = Module.preRun || [];
Module.preRun.push(function () {
  ENV.DISPLAY = ':0';
  FS.mkdir('/libsdl');
  FS.mount(IDBFS, {}, '/libsdl');
  addRunDependency('downstroke-storage');
  FS.syncfs(true, function (err) {
    if (err) console.error('downstroke: reading the browser storage failed', err);
    removeRunDependency('downstroke-storage');
  });
});
