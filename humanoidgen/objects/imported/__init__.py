"""Objects we did not make: meshes and articulated models imported from files (`hgen assets import`), their
annotations transferred from the family's template, and the library of real meshes fetched from pip packages.

formats.py is the one place a file format is registered; importer.py writes a model folder (model_file.py)
atomically; build.py adds one to a scene; transfer.py carries the family's annotations over; fetch.py brings
in the library."""
