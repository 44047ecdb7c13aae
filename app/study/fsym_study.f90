!> The main job: the study of S. A. Chin, *Forward and non-forward symplectic integrators in
!> solving classical dynamics problems*, Int. J. Comput. Math. 84(6), 729-747 (2007),
!> doi:10.1080/00207160701458476, arXiv:0704.3273, on its e = 0.9 Kepler orbit. One scene
!> per figure of the paper, each written to `<out>/<scene>.h5` (H5MD 1.1, see
!> doc/h5-layout.md); the `results` scene writes `<out>/results.h5`, from which
!> scripts/report_results.py renders doc/results.md.
!>
!>     fsym-study [--all] [--scene NAME]... [--out DIR] [--list]
!>
!> Coefficient scenes (eng*) record the energy and precession error coefficients of every
!> step over two periods at eps = P/5000 and no force points; force-point scenes (back*)
!> trace two steps at eps = P/400 from two steps before the pericentre (t = P/2) and write
!> no coefficient curves. Scans: M2 over t1 (zero of the precession at t = P) and GFR5
!> over alpha (least energy and least precession error). Default: `--all`.
program fsym_study
    use, intrinsic :: iso_fortran_env, only: output_unit
    use fsym_study_scenes, only: SCENES, study_t, study_init, study_scene, study_say, &
                                 study_die
    implicit none
    character(len=512) :: arg, val, outdir
    type(study_t) :: cx
    logical :: want(size(SCENES)), any_scene
    integer :: i, j, n

    outdir = 'out'
    want = .false.
    any_scene = .false.
    n = command_argument_count()
    i = 0
    do while (i < n)
        i = i + 1
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--all')
            want = .true.; any_scene = .true.
        case ('--list')
            write (output_unit, '(a)') (trim(SCENES(j)), j=1, size(SCENES))
            stop
        case ('--scene', '--out')
            if (i == n) call study_die(trim(arg)//' needs a value')
            i = i + 1
            call get_command_argument(i, val)
            if (arg == '--out') then
                outdir = val
            else
                any_scene = .true.
                j = scene_index(val)
                if (j == 0) call study_die('unknown scene "'//trim(val)//'" (see --list)')
                want(j) = .true.
            end if
        case ('-h', '--help')
            write (output_unit, '(a)') 'usage: fsym-study [--all] [--scene NAME]... '// &
                '[--out DIR] [--list]'
            stop
        case default
            call study_die('unknown argument "'//trim(arg)//'"')
        end select
    end do
    if (.not. any_scene) want = .true.
    call study_init(cx, trim(outdir))
    do j = 1, size(SCENES)
        if (want(j)) call study_scene(cx, SCENES(j))
    end do
    call study_say('done')

contains

    integer function scene_index(name)
        character(len=*), intent(in) :: name
        integer :: k
        scene_index = 0
        do k = 1, size(SCENES)
            if (trim(SCENES(k)) == trim(name)) scene_index = k
        end do
    end function scene_index

end program fsym_study
