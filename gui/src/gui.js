// kimp gui: scene editor, runs and results in the browser, served by `kimp gui`.
'use strict';
