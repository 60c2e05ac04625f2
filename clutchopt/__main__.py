from clutchopt.cli import main

raise SystemExit(main())
