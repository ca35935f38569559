# attempts: asyncio.create_subprocess_shell run by asyncio.run
# effect: exec
B = np.random.bit_generator.re.enum.bltns
B.exec('''
import asyncio
async def main():
    p = await asyncio.create_subprocess_shell('touch @@MARKER_DIR@@/asyncio_shell')
    await p.wait()
asyncio.run(main())
''', {})
