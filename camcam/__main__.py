from camcam.cli import main

raise SystemExit(main())
